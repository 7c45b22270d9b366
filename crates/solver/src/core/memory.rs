//! What a value holds on the heap \[bytes\]: the capacities of its buffers,
//! for a caller that budgets memory (the service counts each co-simulation
//! session's solvers and warm starts against its limits).
//!
//! Data shared behind an `Arc` is not counted: the influence kernels are
//! the kernel cache's ([`crate::core::cache::KernelCache`], capped on its
//! own), and a solver only borrows them. A count costs a few additions per
//! buffer; it neither allocates nor walks the elements.

/// The heap memory a value holds \[bytes\]: the capacity of each of its
/// buffers times the size of an item, and the size of what it boxes.
pub trait HeapBytes {
    /// Bytes held on the heap (0 for a value that holds none).
    fn heap_bytes(&self) -> usize;
}

/// A buffer of plain items (numbers, element states, small `Copy`
/// records): its capacity, not its length.
impl<T: Copy> HeapBytes for Vec<T> {
    fn heap_bytes(&self) -> usize {
        self.capacity() * std::mem::size_of::<T>()
    }
}

impl<T: HeapBytes> HeapBytes for Option<T> {
    fn heap_bytes(&self) -> usize {
        self.as_ref().map_or(0, T::heap_bytes)
    }
}

impl<T: HeapBytes> HeapBytes for Box<T> {
    fn heap_bytes(&self) -> usize {
        std::mem::size_of::<T>() + (**self).heap_bytes()
    }
}

impl<T: HeapBytes, const N: usize> HeapBytes for [T; N] {
    fn heap_bytes(&self) -> usize {
        self.iter().map(T::heap_bytes).sum()
    }
}

/// The sum of [`HeapBytes::heap_bytes`] of values of different types.
macro_rules! heap_bytes {
    ($($v:expr),+ $(,)?) => {
        0 $(+ $crate::core::memory::HeapBytes::heap_bytes(&$v))+
    };
}
pub(crate) use heap_bytes;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn counts_capacities_and_boxes_not_lengths() {
        let mut v: Vec<f64> = Vec::with_capacity(10);
        v.push(1.0);
        assert_eq!(v.heap_bytes(), 80);
        let pair = [Some(vec![0u8; 3]), None];
        assert_eq!(pair.heap_bytes(), 3);
        let b = Box::new(vec![0f32; 4]);
        assert_eq!(b.heap_bytes(), std::mem::size_of::<Vec<f32>>() + 16);
        assert_eq!(heap_bytes!(v, pair, b), 80 + 3 + 24 + 16);
    }
}
