//! Placed profile pairs shared by content: [`PairCache`].
//!
//! A [`WheelRailPair`] costs a few milliseconds to build (both profiles
//! fitted, placed and sampled on both sides; more for dense profiles) and
//! is read-only afterwards. Callers that build pairs from inputs they do
//! not control (the CONTACT-compatible library's result elements, on the
//! simulator's side and on a server that serves many simulators) ask the
//! cache instead: equal inputs give the same `Arc`, so a pair is built once
//! while anyone uses it.
//!
//! The cache holds its pairs weakly: a pair lives as long as a caller
//! holds it and is freed with the last holder, so the cache itself never
//! keeps memory that no one uses and needs no size limit. Entries whose
//! pair has gone are dropped at the next insertion.
//!
//! The key is the inputs' full content (every point and weight of both
//! profiles and their kinds, the track and wheelset numbers and the spline
//! options, as exact bit patterns), compared exactly: no hash collision can
//! hand one caller another's pair. Profile names and paths are not part of
//! it: the same profile read from two paths is one pair (names appear only
//! in the errors of a build, and a failed build is not cached).

use std::collections::HashMap;
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::{Arc, Mutex, OnceLock, Weak};

use crate::wheelrail::profile::ProfileKind;
use crate::wheelrail::{
    Profile, RailPlacement, SplineOptions, TrackData, WheelRailError, WheelRailPair, WheelsetData,
};

/// Placed profile pairs by content, held weakly (module docs).
#[derive(Default)]
pub struct PairCache {
    pairs: Mutex<HashMap<Vec<u8>, Weak<WheelRailPair>>>,
    hits: AtomicU64,
    builds: AtomicU64,
}

/// What a [`PairCache`] has done and holds.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct PairCacheStats {
    /// Requests answered with a pair already built.
    pub hits: u64,
    /// Pairs built (successfully or not).
    pub builds: u64,
    /// Pairs alive now (held by some caller).
    pub live: usize,
}

impl PairCache {
    /// An empty cache.
    pub fn new() -> Self {
        Self::default()
    }

    /// The process's cache.
    pub fn global() -> &'static PairCache {
        static CACHE: OnceLock<PairCache> = OnceLock::new();
        CACHE.get_or_init(PairCache::new)
    }

    /// The pair of these inputs ([`WheelRailPair::new`]'s arguments): the
    /// one a caller holds already, or a new one. A failed build returns
    /// its error and caches nothing. Two callers that ask for the same new
    /// pair at once may both build it; both get the first one stored.
    pub fn get_or_build(
        &self,
        rails: [&Profile; 2],
        wheels: [&Profile; 2],
        track: TrackData,
        wheelset: WheelsetData,
        spline: &SplineOptions,
    ) -> Result<Arc<WheelRailPair>, WheelRailError> {
        let key = key(rails, wheels, &track, &wheelset, spline);
        if let Some(pair) = self.lock().get(&key).and_then(Weak::upgrade) {
            self.hits.fetch_add(1, Ordering::Relaxed);
            return Ok(pair);
        }
        // Built without the lock: a build takes milliseconds and other
        // pairs need not wait for it.
        self.builds.fetch_add(1, Ordering::Relaxed);
        let built = Arc::new(WheelRailPair::new(rails, wheels, track, wheelset, spline)?);
        let mut pairs = self.lock();
        if let Some(first) = pairs.get(&key).and_then(Weak::upgrade) {
            return Ok(first);
        }
        pairs.retain(|_, p| p.strong_count() > 0);
        pairs.insert(key, Arc::downgrade(&built));
        Ok(built)
    }

    /// Requests, builds and live pairs.
    pub fn stats(&self) -> PairCacheStats {
        let live = self
            .lock()
            .values()
            .filter(|p| p.strong_count() > 0)
            .count();
        PairCacheStats {
            hits: self.hits.load(Ordering::Relaxed),
            builds: self.builds.load(Ordering::Relaxed),
            live,
        }
    }

    fn lock(&self) -> std::sync::MutexGuard<'_, HashMap<Vec<u8>, Weak<WheelRailPair>>> {
        self.pairs.lock().unwrap_or_else(|e| e.into_inner())
    }
}

/// The inputs' content as bytes: equal bytes, equal pair.
fn key(
    rails: [&Profile; 2],
    wheels: [&Profile; 2],
    track: &TrackData,
    wheelset: &WheelsetData,
    spline: &SplineOptions,
) -> Vec<u8> {
    let size: usize = rails
        .iter()
        .chain(&wheels)
        .map(|p| 24 * p.points().len() + 16)
        .sum();
    let mut k = Vec::with_capacity(size + 96);
    let num = |k: &mut Vec<u8>, v: f64| k.extend_from_slice(&v.to_bits().to_le_bytes());
    for p in rails.iter().chain(&wheels) {
        k.push(match p.kind() {
            None => 0,
            Some(ProfileKind::Rail) => 1,
            Some(ProfileKind::Wheel) => 2,
        });
        k.extend_from_slice(&(p.points().len() as u64).to_le_bytes());
        for [y, z] in p.points() {
            num(&mut k, *y);
            num(&mut k, *z);
        }
        k.extend_from_slice(&(p.weights().len() as u64).to_le_bytes());
        for w in p.weights() {
            num(&mut k, *w);
        }
    }
    let (tag, [a, b]) = match track.placement {
        RailPlacement::GaugePoint {
            gauge_m,
            gauge_height_m,
        } => (0, [gauge_m, gauge_height_m]),
        RailPlacement::Origin { q_m, z_m } => (1, [q_m, z_m]),
    };
    k.push(tag);
    for v in [
        a,
        b,
        track.cant_rad,
        track.deviations[0].dy_m,
        track.deviations[0].dz_m,
        track.deviations[0].droll_rad,
        track.deviations[1].dy_m,
        track.deviations[1].dz_m,
        track.deviations[1].droll_rad,
        wheelset.flange_back_distance_m,
        wheelset.nominal_radius_m,
        spline.smoothing_wavelength_m,
    ] {
        num(&mut k, v);
    }
    num(&mut k, track.roller_radius_m.unwrap_or(0.0));
    num(&mut k, track.curvature_per_m);
    match wheelset.flange_back_y_m {
        None => k.push(0),
        Some(y) => {
            k.push(1);
            num(&mut k, y);
        }
    }
    k
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::wheelrail::builtin;
    use crate::wheelrail::profile::{LoadOptions, ProfileChecks};

    fn inputs() -> (Profile, Profile, TrackData, WheelsetData) {
        let load = |name| {
            builtin::profile(name, &LoadOptions::default())
                .expect("a built-in profile")
                .expect("it parses")
        };
        (
            load("MBench_UIC60_v3.prr"),
            load("MBench_S1002_v3.prw"),
            builtin::MBENCH_TRACK,
            builtin::MBENCH_WHEELSET,
        )
    }

    #[test]
    fn equal_inputs_share_one_pair_while_it_is_held() {
        let cache = PairCache::new();
        let (rail, wheel, track, ws) = inputs();
        let spline = SplineOptions::default();
        let build = |c: &PairCache, track: TrackData| {
            c.get_or_build([&rail, &rail], [&wheel, &wheel], track, ws, &spline)
                .unwrap()
        };
        let a = build(&cache, track);
        let b = build(&cache, track);
        assert!(Arc::ptr_eq(&a, &b));
        let wider = TrackData::gauge_point(1.436, 0.014, track.cant_rad);
        let c = build(&cache, wider);
        assert!(!Arc::ptr_eq(&a, &c));
        assert_eq!(
            cache.stats(),
            PairCacheStats {
                hits: 1,
                builds: 2,
                live: 2
            }
        );
        // Freed with its last holder; asked again, built again.
        drop((a, b));
        assert_eq!(cache.stats().live, 1);
        let _d = build(&cache, track);
        assert_eq!(cache.stats().builds, 3);
    }

    #[test]
    fn a_failed_build_is_not_cached() {
        let cache = PairCache::new();
        let (rail, wheel, track, ws) = inputs();
        let spline = SplineOptions::default();
        // The wheel as the rail: refused by its kind, every time.
        for _ in 0..2 {
            let e = cache
                .get_or_build([&wheel, &wheel], [&wheel, &wheel], track, ws, &spline)
                .unwrap_err();
            assert!(e.to_string().contains("track.rail_profile"), "{e}");
        }
        assert_eq!(cache.stats().live, 0);
        assert_eq!(cache.stats().builds, 2);
        let ok = cache.get_or_build([&rail; 2], [&wheel; 2], track, ws, &spline);
        assert!(ok.is_ok());
        // The same points without a kind are another key.
        let plain =
            Profile::from_points("plain", None, wheel.points(), &ProfileChecks::default()).unwrap();
        assert_ne!(
            key([&plain; 2], [&wheel; 2], &track, &ws, &spline),
            key([&wheel; 2], [&wheel; 2], &track, &ws, &spline)
        );
    }
}
