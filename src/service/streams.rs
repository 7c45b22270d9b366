//! Calls open at once, and streamed responses whose client stops reading.
//!
//! HTTP/2 bounds the calls (streams) of one connection
//! (`max_streams_per_connection`) but not of a server: 200 connections of
//! 256 silent streams each held 3.1 GB. [`StreamsLayer`] counts every call
//! from its headers until its response has ended (its body dropped),
//! against `max_streams` for the server and `client_max_streams` per
//! client ([`crate::service::quota`]); a call beyond either is answered at
//! once with RESOURCE_EXHAUSTED naming the setting, before any handler
//! runs. A health check (`grpc.health.v1.Health/Check`) is counted but
//! never refused, so that probes see a busy server as serving.
//!
//! A streamed response (CreepCurve) is written through [`outbound`]: a
//! bounded queue of answers between the solve and tonic. When the client
//! reads nothing, HTTP/2 flow control stops tonic, the queue fills and the
//! solve waits; after `stream_write_timeout_s` of waiting the stream is
//! ended ([`Outbound::fail`]: the queued answers are dropped, its status is
//! what the client reads next), the solve's queue slot and state are
//! freed, and the connection is closed
//! ([`crate::service::connections::ConnState::abort`]), since HTTP/2 holds
//! what it buffered for the stream until the stream or its connection
//! ends, and only the client can end a stream it does not read.

use std::collections::VecDeque;
use std::future::Future;
use std::pin::Pin;
use std::sync::{Arc, Mutex};
use std::task::{Context, Poll, Waker};
use std::time::Duration;

use tokio::sync::Semaphore;
use tokio_stream::Stream;
use tonic::codegen::http;
use tonic::Status;

use crate::service::quota::{ClientId, Quota, QuotaGuard, REFUSED_CALLS_LOG};

/// The health check, never refused by the cap on calls.
const HEALTH_CHECK: &str = "/grpc.health.v1.Health/Check";

/// The tower layer counting open calls (see the module documentation).
#[derive(Clone)]
pub struct StreamsLayer {
    quota: Arc<Quota>,
}

impl StreamsLayer {
    /// Counts calls into `quota` ([`crate::service::quota::Resource::Streams`]).
    pub fn new(quota: Arc<Quota>) -> Self {
        Self { quota }
    }
}

impl<S> tower::Layer<S> for StreamsLayer {
    type Service = Streams<S>;

    fn layer(&self, inner: S) -> Streams<S> {
        Streams {
            inner,
            quota: self.quota.clone(),
        }
    }
}

/// The service of [`StreamsLayer`].
#[derive(Clone)]
pub struct Streams<S> {
    inner: S,
    quota: Arc<Quota>,
}

type BoxFuture<T> = Pin<Box<dyn Future<Output = T> + Send>>;

impl<S, B> tower::Service<http::Request<B>> for Streams<S>
where
    S: tower::Service<http::Request<B>, Response = http::Response<tonic::body::Body>>,
    S::Future: Send + 'static,
    S::Error: Send + 'static,
{
    type Response = http::Response<tonic::body::Body>;
    type Error = S::Error;
    type Future = BoxFuture<Result<Self::Response, S::Error>>;

    fn poll_ready(&mut self, cx: &mut Context<'_>) -> Poll<Result<(), S::Error>> {
        self.inner.poll_ready(cx)
    }

    fn call(&mut self, req: http::Request<B>) -> Self::Future {
        let client = req
            .extensions()
            .get::<ClientId>()
            .cloned()
            .unwrap_or(ClientId::Peer(std::net::Ipv4Addr::UNSPECIFIED.into()));
        let counted = match self.quota.take(&client) {
            Ok(g) => Some(g),
            Err(_) if req.uri().path() == HEALTH_CHECK => None,
            Err(refusal) => {
                if let Some(left_out) = REFUSED_CALLS_LOG.allow() {
                    tracing::info!(
                        path = %crate::service::escaped(req.uri().path()),
                        %client,
                        quota = refusal.setting,
                        left_out,
                        "call refused: {}",
                        refusal.message
                    );
                }
                let status = Status::resource_exhausted(refusal.message);
                return Box::pin(std::future::ready(Ok(status.into_http())));
            }
        };
        let response = self.inner.call(req);
        Box::pin(async move {
            let res = response.await?;
            Ok(res.map(|body| match counted {
                Some(counted) => tonic::body::Body::new(Counted {
                    body,
                    _counted: counted,
                }),
                None => body,
            }))
        })
    }
}

/// A response body that holds its call's count until it is dropped (the
/// call ended: sent whole, reset, or its connection closed).
struct Counted {
    body: tonic::body::Body,
    _counted: QuotaGuard,
}

impl http_body::Body for Counted {
    type Data = tonic::codegen::Bytes;
    type Error = Status;

    fn poll_frame(
        mut self: Pin<&mut Self>,
        cx: &mut Context<'_>,
    ) -> Poll<Option<Result<http_body::Frame<Self::Data>, Self::Error>>> {
        Pin::new(&mut self.body).poll_frame(cx)
    }

    fn is_end_stream(&self) -> bool {
        self.body.is_end_stream()
    }

    fn size_hint(&self) -> http_body::SizeHint {
        self.body.size_hint()
    }
}

/// A bounded queue of `capacity` answers of a streamed response: the
/// sending half for the task that computes them, the stream for tonic.
pub fn outbound<T>(capacity: usize) -> (Outbound<T>, OutboundStream<T>) {
    let shared = Arc::new(Shared {
        space: Semaphore::new(capacity.max(1)),
        state: Mutex::new(Queue {
            items: VecDeque::new(),
            failed: None,
            sender_gone: false,
            reader: None,
        }),
    });
    (
        Outbound {
            shared: shared.clone(),
        },
        OutboundStream { shared },
    )
}

struct Shared<T> {
    /// Free places in the queue; closed when the stream is dropped.
    space: Semaphore,
    state: Mutex<Queue<T>>,
}

struct Queue<T> {
    items: VecDeque<Result<T, Status>>,
    /// The status that ends the stream in place of what was queued.
    failed: Option<Status>,
    sender_gone: bool,
    reader: Option<Waker>,
}

impl<T> Shared<T> {
    fn lock(&self) -> std::sync::MutexGuard<'_, Queue<T>> {
        self.state.lock().unwrap_or_else(|e| e.into_inner())
    }
}

/// Why [`Outbound::send`] did not queue an answer.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Unsent {
    /// The call ended (the client cancelled it or went away).
    Gone,
    /// The queue stayed full for the whole write timeout: the client reads
    /// nothing.
    Stalled,
}

/// The sending half of [`outbound`].
pub struct Outbound<T> {
    shared: Arc<Shared<T>>,
}

impl<T> Outbound<T> {
    /// Queues `item`, waiting at most `timeout` for a place.
    pub async fn send(&self, item: Result<T, Status>, timeout: Duration) -> Result<(), Unsent> {
        match tokio::time::timeout(timeout, self.shared.space.acquire()).await {
            Err(_) => Err(Unsent::Stalled),
            Ok(Err(_)) => Err(Unsent::Gone),
            Ok(Ok(place)) => {
                place.forget();
                let mut q = self.shared.lock();
                q.items.push_back(item);
                if let Some(w) = q.reader.take() {
                    w.wake();
                }
                Ok(())
            }
        }
    }

    /// Ends the stream with `status`: the answers still queued are
    /// dropped (their memory freed now, not when the client reads), and
    /// `status` is what the client reads next.
    pub fn fail(&self, status: Status) {
        let dropped = {
            let mut q = self.shared.lock();
            q.failed = Some(status);
            if let Some(w) = q.reader.take() {
                w.wake();
            }
            std::mem::take(&mut q.items)
        };
        drop(dropped);
        self.shared.space.close();
    }
}

impl<T> Drop for Outbound<T> {
    fn drop(&mut self) {
        let mut q = self.shared.lock();
        q.sender_gone = true;
        if let Some(w) = q.reader.take() {
            w.wake();
        }
    }
}

/// The stream half of [`outbound`], the response tonic sends.
pub struct OutboundStream<T> {
    shared: Arc<Shared<T>>,
}

impl<T> Stream for OutboundStream<T> {
    type Item = Result<T, Status>;

    fn poll_next(self: Pin<&mut Self>, cx: &mut Context<'_>) -> Poll<Option<Self::Item>> {
        let mut q = self.shared.lock();
        if let Some(status) = q.failed.take() {
            q.sender_gone = true;
            return Poll::Ready(Some(Err(status)));
        }
        if let Some(item) = q.items.pop_front() {
            drop(q);
            self.shared.space.add_permits(1);
            return Poll::Ready(Some(item));
        }
        if q.sender_gone {
            return Poll::Ready(None);
        }
        q.reader = Some(cx.waker().clone());
        Poll::Pending
    }
}

impl<T> Drop for OutboundStream<T> {
    fn drop(&mut self) {
        self.shared.space.close();
        let dropped = std::mem::take(&mut self.shared.lock().items);
        drop(dropped);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use tokio_stream::StreamExt;

    #[tokio::test]
    async fn a_reader_gets_what_was_queued_then_the_end() {
        let (tx, mut rx) = outbound::<u32>(2);
        let t = Duration::from_millis(50);
        tx.send(Ok(1), t).await.unwrap();
        tx.send(Ok(2), t).await.unwrap();
        // Full: the third waits, and with nobody reading, stalls.
        assert_eq!(tx.send(Ok(3), t).await, Err(Unsent::Stalled));
        assert_eq!(rx.next().await.unwrap().unwrap(), 1);
        tx.send(Ok(3), t).await.unwrap();
        drop(tx);
        let rest: Vec<u32> = rx.map(|r| r.unwrap()).collect().await;
        assert_eq!(rest, [2, 3]);
    }

    #[tokio::test]
    async fn a_failed_stream_drops_its_queue_and_ends_with_the_status() {
        let (tx, mut rx) = outbound::<Vec<u8>>(4);
        let t = Duration::from_millis(50);
        let big = vec![0u8; 1 << 20];
        tx.send(Ok(big.clone()), t).await.unwrap();
        tx.send(Ok(big), t).await.unwrap();
        tx.fail(Status::deadline_exceeded("stalled"));
        assert!(tx.shared.lock().items.is_empty(), "queue freed at once");
        assert_eq!(tx.send(Ok(vec![]), t).await, Err(Unsent::Gone));
        let s = rx.next().await.unwrap().unwrap_err();
        assert_eq!(s.code(), tonic::Code::DeadlineExceeded);
        assert!(rx.next().await.is_none());
        // A reader that went away: the sender learns it.
        let (tx, rx) = outbound::<u32>(1);
        drop(rx);
        assert_eq!(tx.send(Ok(1), t).await, Err(Unsent::Gone));
    }
}
