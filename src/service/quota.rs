//! Each client's share of the server: who a client is ([`ClientId`]), the
//! counted resources with their server-wide cap and per-client quota
//! ([`Quota`]), the back-off of a peer that fails token checks
//! ([`AuthBackoff`]), and log lines that a flood of refusals cannot
//! multiply ([`LogLimiter`]).
//!
//! A client is the name of its bearer token when the server checks tokens
//! (`auth_tokens_file`; every connection presenting it is the same
//! client), and otherwise its peer address (an IPv6 address by its /64
//! prefix, which one host commonly holds whole). Connections are counted
//! before any token is seen, so always by address.
//!
//! Behind a proxy every peer address is the proxy's. The addresses listed
//! in `trusted_proxies` ([`TrustedProxies`]) are taken at their word: a
//! call from one of them is the client whose address ends its
//! `x-forwarded-for` metadata (the address the proxy saw; what a client
//! wrote there itself comes before it), for the quotas and the token
//! back-off alike, and their connections count against `max_connections`
//! only ([`ClientId::Proxy`]). Anyone else's `x-forwarded-for` is ignored.
//!
//! | resource | server-wide | per client | counted where |
//! |---|---|---|---|
//! | sessions (PatchSession, WheelRailSession, ContactLibrary) | `max_sessions` | `client_max_sessions` | the handlers, from `open` to the stream's end |
//! | requests admitted to the solve pool (running or waiting) | `queue_capacity` | `client_max_admitted` | [`crate::service::pool`] |
//! | calls open (HTTP/2 streams: unary calls, streams, reflection) | `max_streams` | `client_max_streams` | [`crate::service::streams`], a tower layer after the token check |
//! | connections | `max_connections` | `client_max_connections` (by address) | [`crate::service::connections`], at accept |
//!
//! A per-client quota of 0 means half the server-wide cap (rounded up):
//! one client alone can never take everything, and a client running the
//! load test's default mix (16 sessions, each on its own connection, a
//! batch client, the replay) stays far below every share. A client beyond
//! its quota gets RESOURCE_EXHAUSTED naming the quota's setting while
//! others are served; refusals are counted in
//! `railcontact_quota_refused_total{quota}` by the setting's name.

use std::collections::HashMap;
use std::net::{IpAddr, Ipv4Addr, Ipv6Addr};
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

use crate::service::metrics::Metrics;
use crate::service::status::ServiceError;

/// Who a quota counts (see the module documentation).
#[derive(Debug, Clone, PartialEq, Eq, Hash)]
pub enum ClientId {
    /// The name of the bearer token that a checked call presented.
    Token(Arc<str>),
    /// A peer address (IPv4, or an IPv6 /64 prefix; see [`ClientId::peer`]).
    Peer(IpAddr),
    /// A connection of a trusted proxy (`trusted_proxies`): no
    /// per-client quota, its calls are counted by the clients behind it.
    Proxy(IpAddr),
    /// The server's own work (the built-in pair at start): no quota.
    Server,
}

impl ClientId {
    /// The client of a peer address: IPv4 as it is (an IPv4-mapped IPv6
    /// address as its IPv4 address), IPv6 by its /64 prefix.
    pub fn peer(ip: IpAddr) -> Self {
        ClientId::Peer(peer_key(ip))
    }

    /// The client a request was counted as, set by the token check
    /// ([`crate::service::auth`]); a request that passed no such check (a
    /// server built without the layers) is the unspecified address, which
    /// has quotas like any other client.
    pub fn of<T>(req: &tonic::Request<T>) -> Self {
        req.extensions()
            .get::<ClientId>()
            .cloned()
            .unwrap_or(ClientId::Peer(IpAddr::V4(Ipv4Addr::UNSPECIFIED)))
    }
}

/// The key of a peer address: IPv6 by its /64 prefix.
pub fn peer_key(ip: IpAddr) -> IpAddr {
    match ip {
        IpAddr::V4(_) => ip,
        IpAddr::V6(v6) => match v6.to_ipv4_mapped() {
            Some(v4) => IpAddr::V4(v4),
            None => {
                let s = v6.segments();
                IpAddr::V6(Ipv6Addr::new(s[0], s[1], s[2], s[3], 0, 0, 0, 0))
            }
        },
    }
}

impl std::fmt::Display for ClientId {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            ClientId::Token(name) => write!(f, "token `{}`", crate::service::escaped(name)),
            ClientId::Peer(IpAddr::V6(v6)) => write!(f, "address {v6}/64"),
            ClientId::Peer(ip) => write!(f, "address {ip}"),
            ClientId::Proxy(ip) => write!(f, "proxy {ip}"),
            ClientId::Server => f.write_str("the server"),
        }
    }
}

/// A resource counted per client and for the whole server.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Resource {
    /// Open co-simulation sessions.
    Sessions,
    /// Requests admitted to the solve pool, running plus waiting.
    Admitted,
    /// Open calls (HTTP/2 streams).
    Streams,
    /// Open connections.
    Connections,
}

impl Resource {
    /// The setting of the server-wide cap.
    pub fn total_setting(self) -> &'static str {
        match self {
            Resource::Sessions => "max_sessions",
            Resource::Admitted => "queue_capacity",
            Resource::Streams => "max_streams",
            Resource::Connections => "max_connections",
        }
    }

    /// The setting of the per-client quota.
    pub fn client_setting(self) -> &'static str {
        match self {
            Resource::Sessions => "client_max_sessions",
            Resource::Admitted => "client_max_admitted",
            Resource::Streams => "client_max_streams",
            Resource::Connections => "client_max_connections",
        }
    }

    /// What is counted, after a number.
    fn counted(self) -> &'static str {
        match self {
            Resource::Sessions => "sessions open",
            Resource::Admitted => "requests admitted to the solve queue (running or waiting)",
            Resource::Streams => "calls open",
            Resource::Connections => "connections open",
        }
    }

    /// What a refused client may do.
    fn advice(self) -> &'static str {
        match self {
            Resource::Sessions => "close one or retry later",
            Resource::Admitted => "wait for the answers under way, or retry with backoff",
            Resource::Streams => "end calls under way (read or close their streams) or retry later",
            Resource::Connections => "reuse the connections open or close some",
        }
    }
}

/// The per-client quota of a setting: `setting`, or half of `total`
/// (rounded up, at least 1) when it is 0.
pub fn client_share(setting: usize, total: usize) -> usize {
    if setting > 0 {
        setting
    } else {
        total.div_ceil(2).max(1)
    }
}

/// One resource's counts: the server's and each client's, against the
/// server-wide cap and the per-client quota. Cheap to share (`Arc`); a
/// short lock per take and release.
#[derive(Debug)]
pub struct Quota {
    resource: Resource,
    max_total: usize,
    max_client: usize,
    counts: Mutex<Counts>,
    metrics: Arc<Metrics>,
}

#[derive(Debug, Default)]
struct Counts {
    total: usize,
    per_client: HashMap<ClientId, usize>,
}

/// Why [`Quota::take`] refused: which limit, and the message for the
/// client (RESOURCE_EXHAUSTED).
#[derive(Debug, Clone, PartialEq)]
pub struct Refusal {
    /// The setting whose limit was reached (`max_sessions`,
    /// `client_max_sessions`, ...).
    pub setting: &'static str,
    /// What to tell the client.
    pub message: String,
}

impl From<Refusal> for ServiceError {
    fn from(r: Refusal) -> Self {
        ServiceError::Exhausted(r.message)
    }
}

impl Quota {
    /// Counts of `resource`, at most `max_total` for the server (`None`:
    /// the server-wide count is kept elsewhere, e.g. the solve queue's
    /// semaphore) and `max_client` per client; refusals are counted into
    /// `metrics`.
    pub fn new(
        resource: Resource,
        max_total: Option<usize>,
        max_client: usize,
        metrics: Arc<Metrics>,
    ) -> Arc<Self> {
        Arc::new(Self {
            resource,
            max_total: max_total.unwrap_or(usize::MAX),
            max_client: max_client.max(1),
            counts: Mutex::new(Counts::default()),
            metrics,
        })
    }

    /// One more for `client`, released when the guard is dropped; or the
    /// refusal naming the limit reached (the server's first). The server's
    /// own work has no per-client quota.
    pub fn take(self: &Arc<Self>, client: &ClientId) -> Result<QuotaGuard, Refusal> {
        let mut c = self.counts.lock().unwrap_or_else(|e| e.into_inner());
        let r = self.resource;
        let refusal = if c.total >= self.max_total {
            Some(Refusal {
                setting: r.total_setting(),
                message: format!(
                    "{} {} on this server, its limit ({} = {}); {}",
                    c.total,
                    r.counted(),
                    r.total_setting(),
                    self.max_total,
                    r.advice()
                ),
            })
        } else {
            let held = c.per_client.get(client).copied().unwrap_or(0);
            let shared = !matches!(client, ClientId::Server | ClientId::Proxy(_));
            (shared && held >= self.max_client).then(|| Refusal {
                setting: r.client_setting(),
                message: format!(
                    "{client} has {held} {}, its share of this server ({} = {}); {}",
                    r.counted(),
                    r.client_setting(),
                    self.max_client,
                    r.advice()
                ),
            })
        };
        if let Some(refusal) = refusal {
            drop(c);
            self.metrics.quota_refused(refusal.setting);
            return Err(refusal);
        }
        c.total += 1;
        *c.per_client.entry(client.clone()).or_insert(0) += 1;
        self.show(c.total);
        Ok(QuotaGuard {
            quota: self.clone(),
            client: client.clone(),
        })
    }

    /// Held now, by all clients.
    pub fn total(&self) -> usize {
        self.counts.lock().unwrap_or_else(|e| e.into_inner()).total
    }

    /// Held now by `client`.
    pub fn held_by(&self, client: &ClientId) -> usize {
        let c = self.counts.lock().unwrap_or_else(|e| e.into_inner());
        c.per_client.get(client).copied().unwrap_or(0)
    }

    /// Counts a refusal by `setting` made elsewhere (the solve queue's own
    /// cap).
    pub fn refused_by(&self, setting: &'static str) {
        self.metrics.quota_refused(setting);
    }

    /// The per-client quota.
    pub fn client_limit(&self) -> usize {
        self.max_client
    }

    fn release(&self, client: &ClientId) {
        let mut c = self.counts.lock().unwrap_or_else(|e| e.into_inner());
        c.total = c.total.saturating_sub(1);
        if let Some(n) = c.per_client.get_mut(client) {
            *n -= 1;
            if *n == 0 {
                c.per_client.remove(client);
            }
        }
        self.show(c.total);
    }

    /// The gauge of the resources that have one.
    fn show(&self, total: usize) {
        match self.resource {
            Resource::Streams => self.metrics.streams_open(total),
            Resource::Connections => self.metrics.connections_open(total),
            Resource::Sessions | Resource::Admitted => {}
        }
    }
}

/// One unit of a [`Quota`] held by a client; given back when dropped.
#[derive(Debug)]
pub struct QuotaGuard {
    quota: Arc<Quota>,
    client: ClientId,
}

impl Drop for QuotaGuard {
    fn drop(&mut self) {
        self.quota.release(&self.client);
    }
}

/// A trusted proxy's address, or a range of them
/// ([`crate::service::config::ServeConfig::trusted_proxies`]): `10.0.0.5` or `10.244.0.0/16`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct ProxyRange(pub ipnet::IpNet);

impl ProxyRange {
    /// Whether `address` lies in the range (IPv4-mapped IPv6 addresses
    /// and their IPv4 form alike).
    pub fn contains(&self, address: IpAddr) -> bool {
        let net = match self.0 {
            ipnet::IpNet::V6(n) => match n.addr().to_ipv4_mapped() {
                // ::ffff:10.0.0.0/112 is 10.0.0.0/16.
                Some(v4) if n.prefix_len() >= 96 => {
                    ipnet::Ipv4Net::new(v4, n.prefix_len() - 96).map_or(self.0, ipnet::IpNet::V4)
                }
                _ => self.0,
            },
            v4 => v4,
        };
        net.contains(&unmapped(address))
    }
}

impl std::str::FromStr for ProxyRange {
    type Err = String;

    fn from_str(s: &str) -> Result<Self, String> {
        let t = s.trim();
        t.parse::<ipnet::IpNet>()
            .or_else(|_| t.parse::<IpAddr>().map(ipnet::IpNet::from))
            .map(ProxyRange)
            .map_err(|_| {
                format!(
                    "{s:?} is not an IP address (10.0.0.5, fd00::7) or a range in CIDR notation \
                     (10.244.0.0/16)"
                )
            })
    }
}

impl std::fmt::Display for ProxyRange {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self.0.prefix_len() == self.0.max_prefix_len() {
            true => write!(f, "{}", self.0.addr()),
            false => write!(f, "{}", self.0),
        }
    }
}

impl<'de> serde::Deserialize<'de> for ProxyRange {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        let s = <String as serde::Deserialize>::deserialize(d)?;
        s.parse().map_err(serde::de::Error::custom)
    }
}

/// The proxies whose `x-forwarded-for` says who the client is
/// (`trusted_proxies`; see the module documentation).
#[derive(Debug, Clone, Default)]
pub struct TrustedProxies {
    ranges: Vec<ProxyRange>,
}

impl TrustedProxies {
    /// Trusts the proxies in `ranges`.
    pub fn new(ranges: &[ProxyRange]) -> Self {
        Self {
            ranges: ranges.to_vec(),
        }
    }

    /// Whether `remote` is a trusted proxy.
    pub fn trusts(&self, remote: IpAddr) -> bool {
        self.ranges.iter().any(|r| r.contains(remote))
    }

    /// The address of the client of a call that came from `remote` with
    /// the metadata `x_forwarded_for`: the last address listed there when
    /// `remote` is a trusted proxy and it is an address, else `remote`.
    pub fn client_address(&self, remote: IpAddr, x_forwarded_for: Option<&[u8]>) -> IpAddr {
        let forwarded = || {
            let last = std::str::from_utf8(x_forwarded_for?)
                .ok()?
                .rsplit(',')
                .next()?
                .trim();
            last.parse::<IpAddr>()
                .ok()
                .or_else(|| last.parse::<std::net::SocketAddr>().ok().map(|a| a.ip()))
        };
        match self.trusts(remote).then(forwarded).flatten() {
            Some(client) => client,
            None => remote,
        }
    }
}

/// An IPv4-mapped IPv6 address as its IPv4 address; others as they are.
fn unmapped(ip: IpAddr) -> IpAddr {
    match ip {
        IpAddr::V6(v6) => v6.to_ipv4_mapped().map_or(ip, IpAddr::V4),
        IpAddr::V4(_) => ip,
    }
}

/// Peers that present tokens this server does not know: each peer
/// address may fail `burst` checks, then one more per `1 / rate` seconds
/// (a bucket of failures refilling at `rate` per second). While a peer has
/// none left, its calls that need a token are refused with
/// RESOURCE_EXHAUSTED without their token being checked, so a guesser
/// learns nothing from them: about `rate` guesses a second instead of
/// thousands. A missing token or one whose role does not allow the call
/// is no guess and costs nothing.
#[derive(Debug)]
pub struct AuthBackoff {
    burst: f64,
    rate: f64,
    peers: Mutex<HashMap<IpAddr, Bucket>>,
}

#[derive(Debug, Clone, Copy)]
struct Bucket {
    /// Failures left.
    level: f64,
    at: Instant,
}

/// Peers tracked before the full buckets (peers that stopped failing) are
/// dropped.
const MAX_TRACKED_PEERS: usize = 4096;

impl AuthBackoff {
    /// `burst` failures at once, refilled at `rate` per second.
    pub fn new(burst: u32, rate: f64) -> Self {
        Self {
            burst: f64::from(burst.max(1)),
            rate,
            peers: Mutex::new(HashMap::new()),
        }
    }

    fn level(&self, b: &Bucket, now: Instant) -> f64 {
        (b.level + now.duration_since(b.at).as_secs_f64() * self.rate).min(self.burst)
    }

    /// How long `peer` must wait before its next token is checked; None
    /// when it may be checked now.
    pub fn wait(&self, peer: IpAddr) -> Option<Duration> {
        let peers = self.peers.lock().unwrap_or_else(|e| e.into_inner());
        let b = peers.get(&peer)?;
        let level = self.level(b, Instant::now());
        (level < 1.0).then(|| Duration::from_secs_f64((1.0 - level) / self.rate))
    }

    /// `peer` presented a token that is not known.
    pub fn failed(&self, peer: IpAddr) {
        let now = Instant::now();
        let mut peers = self.peers.lock().unwrap_or_else(|e| e.into_inner());
        if peers.len() >= MAX_TRACKED_PEERS && !peers.contains_key(&peer) {
            peers.retain(|_, b| self.level(b, now) < self.burst);
        }
        let level = peers.get(&peer).map_or(self.burst, |b| self.level(b, now));
        peers.insert(
            peer,
            Bucket {
                level: (level - 1.0).max(0.0),
                at: now,
            },
        );
    }
}

/// Log lines of one kind (refusals of calls and connections) at most
/// `lines` per `window`: a client that provokes thousands of refusals a
/// second must not fill the log. A line logged after some were left out
/// says how many ([`LogLimiter::allow`]).
#[derive(Debug)]
pub struct LogLimiter {
    lines: u32,
    window: Duration,
    state: Mutex<Option<LimiterState>>,
}

#[derive(Debug)]
struct LimiterState {
    start: Instant,
    logged: u32,
    left_out: u64,
}

impl LogLimiter {
    /// At most `lines` a `window`.
    pub const fn new(lines: u32, window: Duration) -> Self {
        Self {
            lines,
            window,
            state: Mutex::new(None),
        }
    }

    /// Whether to log a line now: `Some(n)` with the number of lines left
    /// out since the last one logged, None to leave this one out.
    pub fn allow(&self) -> Option<u64> {
        let now = Instant::now();
        let mut guard = self.state.lock().unwrap_or_else(|e| e.into_inner());
        let s = guard.get_or_insert(LimiterState {
            start: now,
            logged: 0,
            left_out: 0,
        });
        if now.duration_since(s.start) >= self.window {
            s.start = now;
            s.logged = 0;
        }
        if s.logged < self.lines {
            s.logged += 1;
            Some(std::mem::take(&mut s.left_out))
        } else {
            s.left_out += 1;
            None
        }
    }
}

/// Lines about refused calls (tokens, quotas): 20 per 10 s.
pub static REFUSED_CALLS_LOG: LogLimiter = LogLimiter::new(20, Duration::from_secs(10));

/// Lines about refused or closed connections: 20 per 10 s.
pub static CONNECTIONS_LOG: LogLimiter = LogLimiter::new(20, Duration::from_secs(10));

#[cfg(test)]
mod tests {
    use super::*;

    fn peer(ip: &str) -> ClientId {
        ClientId::peer(ip.parse().unwrap())
    }

    #[test]
    fn quotas_count_per_client_and_for_the_server() {
        let q = Quota::new(
            Resource::Sessions,
            Some(3),
            client_share(0, 3),
            Arc::new(Metrics::default()),
        );
        assert_eq!(q.client_limit(), 2);
        let (a, b) = (peer("10.0.0.1"), peer("10.0.0.2"));
        let a1 = q.take(&a).unwrap();
        let _a2 = q.take(&a).unwrap();
        let r = q.take(&a).unwrap_err();
        assert_eq!(r.setting, "client_max_sessions");
        assert!(
            r.message
                .starts_with("address 10.0.0.1 has 2 sessions open, its share")
                && r.message.contains("client_max_sessions = 2"),
            "{}",
            r.message
        );
        let _b1 = q.take(&b).unwrap();
        let r = q.take(&b).unwrap_err();
        assert_eq!(r.setting, "max_sessions", "{}", r.message);
        drop(a1);
        assert_eq!((q.total(), q.held_by(&a)), (2, 1));
        let _b2 = q.take(&b).unwrap();
        // The server's own work has no share, only the cap.
        let q = Quota::new(Resource::Admitted, None, 1, Arc::new(Metrics::default()));
        let _s: Vec<_> = (0..5).map(|_| q.take(&ClientId::Server).unwrap()).collect();
        assert_eq!(q.total(), 5);
    }

    #[test]
    fn ipv6_peers_are_keyed_by_their_64_prefix() {
        assert_eq!(peer("2001:db8:1:2:3:4:5:6"), peer("2001:db8:1:2:ffff::1"));
        assert_ne!(peer("2001:db8:1:2::1"), peer("2001:db8:1:3::1"));
        assert_eq!(peer("::ffff:10.1.2.3"), peer("10.1.2.3"));
        assert_eq!(
            peer("2001:db8:1:2::9").to_string(),
            "address 2001:db8:1:2::/64"
        );
        assert_eq!(ClientId::Token("a\nb".into()).to_string(), "token `a\\nb`");
    }

    #[test]
    fn only_a_trusted_proxy_says_who_its_client_is() {
        let proxy: IpAddr = "10.0.0.5".parse().unwrap();
        let other: IpAddr = "10.0.0.6".parse().unwrap();
        let t = TrustedProxies::new(&["10.0.0.5".parse().unwrap()]);
        let ip = |s: &str| s.parse::<IpAddr>().unwrap();
        // The last entry is the one the proxy appended.
        let h = b"1.2.3.4, 192.0.2.7".as_slice();
        assert_eq!(t.client_address(proxy, Some(h)), ip("192.0.2.7"));
        assert_eq!(
            t.client_address(proxy, Some(b"[2001:db8::1]:443".as_slice())),
            ip("2001:db8::1")
        );
        assert_eq!(t.client_address(other, Some(h)), other, "not trusted");
        assert_eq!(t.client_address(proxy, None), proxy);
        assert_eq!(t.client_address(proxy, Some(b"unknown".as_slice())), proxy);
        assert!(t.trusts("::ffff:10.0.0.5".parse().unwrap()));
        // A proxy's connections have no per-client share.
        let q = Quota::new(
            Resource::Connections,
            Some(3),
            1,
            Arc::new(Metrics::default()),
        );
        let _c: Vec<_> = (0..3)
            .map(|_| q.take(&ClientId::Proxy(proxy)).unwrap())
            .collect();
        assert_eq!(
            q.take(&ClientId::Proxy(proxy)).unwrap_err().setting,
            "max_connections"
        );
    }

    #[test]
    fn a_peer_that_fails_its_burst_waits_for_the_refill() {
        let b = AuthBackoff::new(3, 2.0);
        let p: IpAddr = "10.0.0.9".parse().unwrap();
        for _ in 0..3 {
            assert!(b.wait(p).is_none());
            b.failed(p);
        }
        let failed_at = Instant::now();
        let w = b.wait(p).expect("in back-off");
        // Half a second (one failure at 2 a second) from the last failure,
        // however long the machine took to get here.
        assert!(
            w <= Duration::from_millis(500)
                && w + failed_at.elapsed() >= Duration::from_millis(499),
            "{w:?}"
        );
        assert!(
            b.wait("10.0.0.10".parse().unwrap()).is_none(),
            "others are not"
        );
        std::thread::sleep(w + Duration::from_millis(20));
        assert!(b.wait(p).is_none(), "refilled");
    }

    #[test]
    fn the_log_limiter_counts_what_it_left_out() {
        let l = LogLimiter::new(2, Duration::from_secs(1));
        assert_eq!(l.allow(), Some(0));
        assert_eq!(l.allow(), Some(0));
        assert_eq!(l.allow(), None);
        assert_eq!(l.allow(), None);
        std::thread::sleep(Duration::from_millis(1050));
        assert_eq!(l.allow(), Some(2));
    }
}
