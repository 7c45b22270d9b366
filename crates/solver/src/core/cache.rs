//! Cache of transformed influence kernels, keyed by everything they depend on:
//! grid dimensions, element size, both materials and the operator kind. The
//! service keeps one per process; building a 64x64 set costs a few ms, a hit
//! costs a hash lookup.
//!
//! Memory is capped: when the kernels held exceed `max_bytes`, the least
//! recently used sets are dropped (solvers still holding one keep it alive
//! until they finish; the cache only forgets it). The first use of a key
//! builds its kernels once, however many threads ask at the same time: the
//! others wait for that build instead of repeating it.
//!
//! A viscoelastic set (seconds of numerical integration) built for a caller
//! that is cancelled ([`crate::core::cancel`]) stops integrating at once:
//! that caller gets the unfinished set (its solve then answers Cancelled
//! without using it), the cache forgets it, and a caller that waited for
//! the same build and is not cancelled builds it again.

use std::collections::HashMap;
use std::sync::atomic::{AtomicU64, Ordering::Relaxed};
use std::sync::{Arc, Mutex, OnceLock};

use crate::core::cancel;
use crate::core::fft::{ConvolutionPlan, KernelSet};
use crate::core::grid::Grid;
use crate::core::influence::{HalfSpaceInfluence, KernelKind};
use crate::core::material::CombinedMaterial;
use crate::core::numerical_influence::InfluenceFile;
use crate::core::viscoelastic::Viscoelastic;

/// Default memory cap of the kernels held \[bytes\]: 1 GiB, some 600 sets of
/// 64 x 64 steady-rolling kernels.
pub const DEFAULT_MAX_BYTES: usize = 1 << 30;

#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
struct Key {
    nx: usize,
    ny: usize,
    dx: u64,
    dy: u64,
    mat: [u64; 4],
    /// An interfacial layer's flexibility (bits; 0 without).
    layer: u64,
    /// Viscoelastic bodies' (f_g, relaxation length) per body (bits;
    /// zeros for elastic bodies).
    visc: [u64; 4],
    /// A file of numerical influence coefficients' fingerprint (None: the
    /// half-space).
    table: Option<u64>,
    kind: KernelKind,
}

/// What a set depends on beyond the grid and the elastic constants: an
/// interfacial layer's flexibility \[m/Pa\] (0: none), viscoelastic bodies,
/// a file of numerical influence coefficients.
#[derive(Default, Clone, Copy)]
struct Bodies<'a> {
    layer: f64,
    visc: Option<&'a Viscoelastic>,
    table: Option<&'a Arc<InfluenceFile>>,
}

/// Whether `set` holds the kernels of `table` (both None: the closed-form
/// ones). The key holds a 64-bit fingerprint of a file, and files come
/// from clients of the service: two different files with one fingerprint
/// (made on purpose) must not share kernels, so a hit compares the
/// contents (microseconds for a file of 100 kB); a different file is built
/// for its caller alone, not cached.
fn same_table(set: &KernelSet, table: Option<&Arc<InfluenceFile>>) -> bool {
    match (&set.table, table) {
        (Some(s), Some(t)) => Arc::ptr_eq(s, t) || **s == **t,
        (None, None) => true,
        _ => false,
    }
}

/// One entry: the kernels once built, when it was last used, its size.
/// A build: the set, and whether it is whole (false: a cancelled
/// caller's viscoelastic build, which stopped integrating).
type Built = (Arc<KernelSet>, bool);

struct Entry {
    cell: Arc<OnceLock<Built>>,
    last_used: u64,
    /// 0 until the build is accounted.
    bytes: usize,
}

struct Inner {
    map: HashMap<Key, Entry>,
    plans: HashMap<(usize, usize), Arc<ConvolutionPlan>>,
    clock: u64,
    bytes: usize,
    max_bytes: usize,
}

/// Figures of a cache, for metrics.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct CacheStats {
    /// Look-ups that found the kernels built (or being built).
    pub hits: u64,
    /// Look-ups that built them.
    pub misses: u64,
    /// Sets dropped to stay under the memory cap.
    pub evictions: u64,
    /// Sets held.
    pub entries: usize,
    /// Memory of the sets held \[bytes\].
    pub bytes: usize,
    /// The memory cap \[bytes\].
    pub max_bytes: usize,
}

/// Thread-safe kernel cache with a memory cap and least-recently-used
/// eviction. No lock is held while kernels are built.
pub struct KernelCache {
    inner: Mutex<Inner>,
    hits: AtomicU64,
    misses: AtomicU64,
    evictions: AtomicU64,
}

impl Default for KernelCache {
    fn default() -> Self {
        Self::new(DEFAULT_MAX_BYTES)
    }
}

impl KernelCache {
    /// A cache holding kernels of at most `max_bytes` (at least the most
    /// recently used set is always kept).
    pub fn new(max_bytes: usize) -> Self {
        Self {
            inner: Mutex::new(Inner {
                map: HashMap::new(),
                plans: HashMap::new(),
                clock: 0,
                bytes: 0,
                max_bytes,
            }),
            hits: AtomicU64::new(0),
            misses: AtomicU64::new(0),
            evictions: AtomicU64::new(0),
        }
    }

    /// The process-wide cache.
    pub fn global() -> &'static KernelCache {
        static CACHE: OnceLock<KernelCache> = OnceLock::new();
        CACHE.get_or_init(KernelCache::default)
    }

    fn lock(&self) -> std::sync::MutexGuard<'_, Inner> {
        self.inner.lock().unwrap_or_else(|e| e.into_inner())
    }

    /// Changes the memory cap, evicting at once if needed.
    pub fn set_max_bytes(&self, max_bytes: usize) {
        let mut inner = self.lock();
        inner.max_bytes = max_bytes;
        self.evict(&mut inner, None);
    }

    /// (hits, misses) so far.
    pub fn stats(&self) -> (u64, u64) {
        (self.hits.load(Relaxed), self.misses.load(Relaxed))
    }

    /// All figures.
    pub fn figures(&self) -> CacheStats {
        let inner = self.lock();
        CacheStats {
            hits: self.hits.load(Relaxed),
            misses: self.misses.load(Relaxed),
            evictions: self.evictions.load(Relaxed),
            entries: inner.map.len(),
            bytes: inner.bytes,
            max_bytes: inner.max_bytes,
        }
    }

    /// The kernel set for this grid, material pair and kind, built on a miss.
    pub fn get(
        &self,
        grid: &Grid,
        material: &CombinedMaterial,
        kind: KernelKind,
    ) -> Arc<KernelSet> {
        self.get_with(grid, material, Bodies::default(), kind, None)
    }

    /// [`KernelCache::get`] with the coefficients of a file of numerical
    /// influence coefficients instead of the half-space's
    /// ([`KernelSet::from_table`]); None is [`KernelCache::get`]'s set.
    /// The caller has checked the file against the grid
    /// ([`InfluenceFile::check_grid`]).
    pub fn get_numerical(
        &self,
        grid: &Grid,
        material: &CombinedMaterial,
        table: Option<&Arc<InfluenceFile>>,
        kind: KernelKind,
    ) -> Arc<KernelSet> {
        let bodies = Bodies {
            table,
            ..Bodies::default()
        };
        self.get_with(grid, material, bodies, kind, None)
    }

    /// [`KernelCache::get`] with an interfacial layer of tangential
    /// flexibility `layer_flexibility_m_per_pa` between the bodies
    /// ([`HalfSpaceInfluence::with_layer_flexibility`]); 0 is
    /// [`KernelCache::get`]'s set.
    pub fn get_layered(
        &self,
        grid: &Grid,
        material: &CombinedMaterial,
        layer_flexibility_m_per_pa: f64,
        kind: KernelKind,
    ) -> Arc<KernelSet> {
        self.get_viscoelastic(grid, material, layer_flexibility_m_per_pa, None, kind)
    }

    /// [`KernelCache::get_layered`] with viscoelastic bodies in steady
    /// rolling ([`HalfSpaceInfluence::with_viscoelastic`]; None: elastic).
    pub fn get_viscoelastic(
        &self,
        grid: &Grid,
        material: &CombinedMaterial,
        layer_flexibility_m_per_pa: f64,
        visc: Option<&Viscoelastic>,
        kind: KernelKind,
    ) -> Arc<KernelSet> {
        let layer = layer_flexibility_m_per_pa;
        let bodies = Bodies {
            layer,
            visc,
            table: None,
        };
        self.get_with(grid, material, bodies, kind, None)
    }

    /// [`KernelCache::get`] for a caller that holds the other kind's set of
    /// the same grid and materials: a miss takes the tangential inverse,
    /// the same for both kinds, from `other`
    /// ([`KernelSet::sharing_inverse_of`]) instead of building it again.
    pub fn get_sharing_inverse(
        &self,
        grid: &Grid,
        material: &CombinedMaterial,
        kind: KernelKind,
        other: &KernelSet,
    ) -> Arc<KernelSet> {
        self.get_with(
            grid,
            material,
            Bodies {
                layer: other.influence.layer_flexibility_m_per_pa(),
                visc: other.influence.viscoelastic().as_ref(),
                table: other.table.as_ref(),
            },
            kind,
            Some(other),
        )
    }

    fn get_with(
        &self,
        grid: &Grid,
        material: &CombinedMaterial,
        bodies: Bodies<'_>,
        kind: KernelKind,
        other: Option<&KernelSet>,
    ) -> Arc<KernelSet> {
        let Bodies { layer, visc, table } = bodies;
        // -0 and 0 are the same layer (none).
        let layer = if layer == 0.0 { 0.0 } else { layer };
        // Elastic bodies given as viscoelastic ones (f_g = 0) are elastic.
        let visc = visc.filter(|v| !(v.body1.is_elastic() && v.body2.is_elastic()));
        let relaxation = visc.map_or([(0.0, 0.0); 2], |v| v.relaxation());
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
            layer: layer.to_bits(),
            visc: [
                relaxation[0].0.to_bits(),
                relaxation[0].1.to_bits(),
                relaxation[1].0.to_bits(),
                relaxation[1].1.to_bits(),
            ],
            table: table.map(|t| t.fingerprint()),
            kind,
        };
        let build = |plan: Arc<ConvolutionPlan>| {
            let influence = if grid.is_line() {
                HalfSpaceInfluence::plane_strain(grid.dx_m, material)
            } else {
                HalfSpaceInfluence::new(grid.dx_m, grid.dy_m, material)
            }
            .with_layer_flexibility(layer);
            let influence = match visc {
                Some(v) => influence.with_viscoelastic(material, v),
                None => influence,
            };
            Arc::new(match (table, other) {
                (Some(t), other) => KernelSet::from_table(plan, influence, kind, t.clone(), other),
                (None, Some(other)) => KernelSet::sharing_inverse_of(plan, influence, kind, other),
                (None, None) => KernelSet::new(plan, influence, kind),
            })
        };
        loop {
            let (cell, plan) = {
                let mut inner = self.lock();
                inner.clock += 1;
                let now = inner.clock;
                let entry = inner.map.entry(key).or_insert_with(|| Entry {
                    cell: Arc::new(OnceLock::new()),
                    last_used: now,
                    bytes: 0,
                });
                entry.last_used = now;
                let cell = entry.cell.clone();
                let plan = inner
                    .plans
                    .entry((grid.nx, grid.ny))
                    .or_insert_with(|| Arc::new(ConvolutionPlan::new(grid.nx, grid.ny)))
                    .clone();
                if let Some((set, true)) = cell.get() {
                    if !same_table(set, table) {
                        drop(inner);
                        return build(plan);
                    }
                    self.hits.fetch_add(1, Relaxed);
                    return set.clone();
                }
                (cell, plan)
            };
            let mut built = false;
            let (set, whole) = cell
                .get_or_init(|| {
                    built = true;
                    // Cancellation stays once asked: a build it did not cut
                    // short is whole.
                    (build(plan.clone()), visc.is_none() || !cancel::requested())
                })
                .clone();
            if !whole {
                // Forgotten by whoever sees it first; built again for a
                // caller that is not cancelled.
                let mut inner = self.lock();
                if inner
                    .map
                    .get(&key)
                    .is_some_and(|e| Arc::ptr_eq(&e.cell, &cell))
                {
                    inner.map.remove(&key);
                }
                drop(inner);
                if cancel::requested() {
                    return set;
                }
                continue;
            }
            if !built {
                // Another thread built it while this one waited.
                if !same_table(&set, table) {
                    return build(plan);
                }
                self.hits.fetch_add(1, Relaxed);
                return set;
            }
            self.misses.fetch_add(1, Relaxed);
            let mut inner = self.lock();
            let bytes = set.bytes();
            // The entry may have been evicted (and even re-created)
            // meanwhile: account only the entry this build belongs to.
            if let Some(e) = inner.map.get_mut(&key) {
                if Arc::ptr_eq(&e.cell, &cell) && e.bytes == 0 {
                    e.bytes = bytes;
                    inner.bytes += bytes;
                }
            }
            self.evict(&mut inner, Some(key));
            return set;
        }
    }

    /// Drops least recently used entries until the cap holds, never `keep`
    /// and never an entry still being built.
    fn evict(&self, inner: &mut Inner, keep: Option<Key>) {
        while inner.bytes > inner.max_bytes {
            let victim = inner
                .map
                .iter()
                .filter(|(k, e)| Some(**k) != keep && e.bytes > 0)
                .min_by_key(|(_, e)| e.last_used)
                .map(|(k, _)| *k);
            let Some(k) = victim else { break };
            if let Some(e) = inner.map.remove(&k) {
                inner.bytes -= e.bytes;
                self.evictions.fetch_add(1, Relaxed);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::core::material::Material;

    fn material() -> CombinedMaterial {
        CombinedMaterial::identical(Material {
            shear_modulus_pa: 80e9,
            poisson_ratio: 0.28,
        })
        .unwrap()
    }

    fn grid(n: usize) -> Grid {
        Grid::centered(n, n, 0.01, 0.01).unwrap()
    }

    /// A viscoelastic build for a cancelled caller stops integrating, and
    /// the cache does not keep it: the next caller's set is the whole one,
    /// the same as a fresh cache builds.
    #[test]
    fn a_cancelled_viscoelastic_build_is_cut_short_and_not_kept() {
        use crate::core::cancel::CancelToken;
        use crate::core::viscoelastic::Sls;
        let (m, g, k) = (material(), grid(8), KernelKind::SteadyRolling);
        let sls = Sls {
            relaxation_ratio: 2.0,
            creep_relaxation_time_s: 0.002,
        };
        let visc = Viscoelastic {
            rolling_speed_m_per_s: 10.0,
            body1: sls,
            body2: sls,
        };
        let whole = KernelCache::default()
            .get_viscoelastic(&g, &m, 0.0, Some(&visc), k)
            .tangential_norm_bound;
        let cache = KernelCache::default();
        let token = CancelToken::new();
        token.cancel();
        let cut = token.scope(|| cache.get_viscoelastic(&g, &m, 0.0, Some(&visc), k));
        assert_ne!(cut.tangential_norm_bound, whole, "the integration stopped");
        assert_eq!(cache.figures().entries, 0, "not kept");
        let again = cache.get_viscoelastic(&g, &m, 0.0, Some(&visc), k);
        assert_eq!(again.tangential_norm_bound.to_bits(), whole.to_bits());
        assert!(Arc::ptr_eq(
            &again,
            &cache.get_viscoelastic(&g, &m, 0.0, Some(&visc), k)
        ));
    }

    #[test]
    fn hits_share_one_set_and_the_memory_cap_evicts_the_least_recently_used() {
        let m = material();
        let k = KernelKind::Displacement;
        let one = KernelCache::default().get(&grid(16), &m, k).bytes();
        assert!(one > 0);
        // Room for two sets of this size.
        let cache = KernelCache::new(2 * one + one / 2);
        let a = cache.get(&grid(16), &m, k);
        let b = cache.get(&Grid::centered(16, 16, 0.02, 0.02).unwrap(), &m, k);
        assert!(Arc::ptr_eq(&a, &cache.get(&grid(16), &m, k)));
        // `a` was used last: the third set evicts `b`.
        let _c = cache.get(&Grid::centered(16, 16, 0.03, 0.03).unwrap(), &m, k);
        let f = cache.figures();
        assert_eq!((f.entries, f.evictions), (2, 1), "{f:?}");
        assert!(f.bytes <= f.max_bytes, "{f:?}");
        assert!(Arc::ptr_eq(&a, &cache.get(&grid(16), &m, k)));
        let b2 = cache.get(&Grid::centered(16, 16, 0.02, 0.02).unwrap(), &m, k);
        assert!(!Arc::ptr_eq(&b, &b2), "b was evicted and rebuilt");
        let f = cache.figures();
        assert_eq!((f.hits, f.misses), (2, 4), "{f:?}");
        // A cap below one set keeps the newest only.
        cache.set_max_bytes(1);
        let f = cache.figures();
        assert_eq!(f.entries, 0, "{f:?}");
    }

    /// Two different files claiming one fingerprint (a collision a client
    /// could make on purpose) do not share kernels: the second is built
    /// for its caller and not cached; the first stays a hit.
    #[test]
    fn files_with_one_fingerprint_do_not_share_kernels() {
        use crate::core::influence::Component;
        use crate::core::numerical_influence::UpperBody;
        let (m, g, k) = (material(), grid(8), KernelKind::Displacement);
        let file = |scale: f64| {
            InfluenceFile::from_coefficients(
                1,
                (8, 8),
                (0.01 / 8.0, 0.01 / 8.0),
                UpperBody::Rail,
                |_, i, j, ox, oy| {
                    let d = if i == j { 1.0 } else { 0.0 };
                    scale * d / (1.0 + (ox * ox + oy * oy) as f64)
                        + if (i, j) == (Component::N, Component::N) {
                            0.1
                        } else {
                            0.0
                        }
                },
            )
            .unwrap()
        };
        let a = Arc::new(file(1.0));
        let b = Arc::new(file(2.0).with_fingerprint(a.fingerprint()));
        assert_ne!(*a, *b);
        let cache = KernelCache::default();
        let sa = cache.get_numerical(&g, &m, Some(&a), k);
        let sb = cache.get_numerical(&g, &m, Some(&b), k);
        assert!(!Arc::ptr_eq(&sa, &sb));
        assert!(Arc::ptr_eq(sb.table.as_ref().unwrap(), &b));
        let xx = |s: &KernelSet| s.value(Component::X, Component::X, 1, 0).to_bits();
        assert_ne!(xx(&sa), xx(&sb));
        assert!(Arc::ptr_eq(&sa, &cache.get_numerical(&g, &m, Some(&a), k)));
        let f = cache.figures();
        assert_eq!((f.entries, f.hits, f.misses), (1, 1, 1), "{f:?}");
    }

    #[test]
    fn concurrent_first_use_builds_once() {
        let cache = Arc::new(KernelCache::default());
        let m = material();
        let sets: Vec<Arc<KernelSet>> = std::thread::scope(|s| {
            let handles: Vec<_> = (0..4)
                .map(|_| s.spawn(|| cache.get(&grid(32), &m, KernelKind::SteadyRolling)))
                .collect();
            handles.into_iter().map(|h| h.join().unwrap()).collect()
        });
        assert!(sets.windows(2).all(|w| Arc::ptr_eq(&w[0], &w[1])));
        assert_eq!(cache.stats(), (3, 1));
    }
}
