//! Cache of transformed influence kernels, keyed by everything they depend on:
//! grid dimensions, element size, both materials and the operator kind. The
//! service keeps one per process; building a 64x64 set costs a few ms, a hit
//! costs a hash lookup.

use std::collections::HashMap;
use std::sync::{Arc, Mutex};

use crate::core::fft::{ConvolutionPlan, KernelSet};
use crate::core::grid::Grid;
use crate::core::influence::{HalfSpaceInfluence, KernelKind};
use crate::core::material::CombinedMaterial;

#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
struct Key {
    nx: usize,
    ny: usize,
    dx: u64,
    dy: u64,
    mat: [u64; 4],
    kind: KernelKind,
}

/// Thread-safe kernel cache. Entries are never evicted (bounded by
/// `max_entries`: the oldest-inserted half is dropped when full).
pub struct KernelCache {
    map: Mutex<HashMap<Key, (u64, Arc<KernelSet>)>>,
    plans: Mutex<HashMap<(usize, usize), Arc<ConvolutionPlan>>>,
    counter: Mutex<u64>,
    max_entries: usize,
    hits: std::sync::atomic::AtomicU64,
    misses: std::sync::atomic::AtomicU64,
}

impl Default for KernelCache {
    fn default() -> Self {
        Self::new(256)
    }
}

impl KernelCache {
    /// A cache holding at most `max_entries` kernel sets.
    pub fn new(max_entries: usize) -> Self {
        Self {
            map: Mutex::new(HashMap::new()),
            plans: Mutex::new(HashMap::new()),
            counter: Mutex::new(0),
            max_entries: max_entries.max(2),
            hits: Default::default(),
            misses: Default::default(),
        }
    }

    /// The process-wide cache.
    pub fn global() -> &'static KernelCache {
        static CACHE: std::sync::OnceLock<KernelCache> = std::sync::OnceLock::new();
        CACHE.get_or_init(KernelCache::default)
    }

    /// (hits, misses) so far.
    pub fn stats(&self) -> (u64, u64) {
        use std::sync::atomic::Ordering::Relaxed;
        (self.hits.load(Relaxed), self.misses.load(Relaxed))
    }

    /// The kernel set for this grid, material pair and kind, built on a miss.
    /// The lock is not held while kernels are built.
    pub fn get(
        &self,
        grid: &Grid,
        material: &CombinedMaterial,
        kind: KernelKind,
    ) -> Arc<KernelSet> {
        use std::sync::atomic::Ordering::Relaxed;
        let key = Key {
            nx: grid.nx,
            ny: grid.ny,
            dx: grid.dx_m.to_bits(),
            dy: grid.dy_m.to_bits(),
            mat: [
                material.body1.shear_modulus_pa.to_bits(),
                material.body1.poisson_ratio.to_bits(),
                material.body2.shear_modulus_pa.to_bits(),
                material.body2.poisson_ratio.to_bits(),
            ],
            kind,
        };
        if let Some((_, k)) = self.map.lock().unwrap_or_else(|e| e.into_inner()).get(&key) {
            self.hits.fetch_add(1, Relaxed);
            return k.clone();
        }
        self.misses.fetch_add(1, Relaxed);
        let plan = {
            let mut plans = self.plans.lock().unwrap_or_else(|e| e.into_inner());
            plans
                .entry((grid.nx, grid.ny))
                .or_insert_with(|| Arc::new(ConvolutionPlan::new(grid.nx, grid.ny)))
                .clone()
        };
        let set = Arc::new(KernelSet::new(
            plan,
            HalfSpaceInfluence::new(grid.dx_m, grid.dy_m, material),
            kind,
        ));
        let stamp = {
            let mut c = self.counter.lock().unwrap_or_else(|e| e.into_inner());
            *c += 1;
            *c
        };
        let mut map = self.map.lock().unwrap_or_else(|e| e.into_inner());
        if map.len() >= self.max_entries {
            let mut stamps: Vec<u64> = map.values().map(|(s, _)| *s).collect();
            stamps.sort_unstable();
            let cut = stamps[stamps.len() / 2];
            map.retain(|_, (s, _)| *s > cut);
        }
        map.entry(key).or_insert((stamp, set)).1.clone()
    }
}
