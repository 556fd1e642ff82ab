//! Sorting with one copy of the standard library's sort per element type.
//!
//! `slice::sort_by` is generic over its comparator, so every call with a closure of its own
//! compiles a sort of its own (driftsort or quicksort with their small-sort networks, 10 to
//! 25 KB of WebAssembly each). Through [`SharedSort`] the comparator is passed as a `dyn`
//! reference instead: all calls for one element type share one sort. The order is exactly that
//! of the standard sorts (`shared_sort_by` is stable, `shared_sort_unstable_by` is not); only an
//! indirect call per comparison is added, which the planner's short lists do not notice.
//!
//! ```
//! use furrow::sort::SharedSort;
//!
//! let mut lengths = vec![3.5, -1.0, 2.25];
//! lengths.shared_sort_by(f64::total_cmp);
//! assert_eq!(lengths, [-1.0, 2.25, 3.5]);
//!
//! let mut names = vec![("b", 2), ("a", 2), ("c", 1)];
//! names.shared_sort_by_key(|&(_, k)| k); // stable: "b" stays before "a"
//! assert_eq!(names, [("c", 1), ("b", 2), ("a", 2)]);
//! ```

use std::cmp::Ordering;

/// Sorts of a slice that share one instance of the sort among every comparator.
pub trait SharedSort<T> {
    /// As [`slice::sort_by`] (stable).
    fn shared_sort_by(&mut self, compare: impl FnMut(&T, &T) -> Ordering);
    /// As [`slice::sort_by_key`] (stable).
    fn shared_sort_by_key<K: Ord>(&mut self, key: impl FnMut(&T) -> K);
    /// As [`slice::sort_unstable_by`].
    fn shared_sort_unstable_by(&mut self, compare: impl FnMut(&T, &T) -> Ordering);
}

impl<T> SharedSort<T> for [T] {
    fn shared_sort_by(&mut self, mut compare: impl FnMut(&T, &T) -> Ordering) {
        stable(self, &mut compare);
    }

    fn shared_sort_by_key<K: Ord>(&mut self, mut key: impl FnMut(&T) -> K) {
        stable(self, &mut |a: &T, b: &T| key(a).cmp(&key(b)));
    }

    fn shared_sort_unstable_by(&mut self, mut compare: impl FnMut(&T, &T) -> Ordering) {
        unstable(self, &mut compare);
    }
}

#[inline(never)]
fn stable<T>(v: &mut [T], compare: &mut dyn FnMut(&T, &T) -> Ordering) {
    v.sort_by(|a, b| compare(a, b));
}

#[inline(never)]
fn unstable<T>(v: &mut [T], compare: &mut dyn FnMut(&T, &T) -> Ordering) {
    v.sort_unstable_by(|a, b| compare(a, b));
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn orders_as_the_standard_sorts() {
        let keys: Vec<(u32, u32)> = (0..200u32).map(|i| ((i * 37) % 11, i)).collect();
        let mut ours = keys.clone();
        ours.shared_sort_by(|a, b| a.0.cmp(&b.0));
        let mut std_sorted = keys.clone();
        std_sorted.sort_by_key(|k| k.0);
        assert_eq!(ours, std_sorted, "stable, as sort_by");
        let mut by_key = keys.clone();
        by_key.shared_sort_by_key(|k| k.0);
        assert_eq!(by_key, std_sorted);
        let mut unstable = keys.clone();
        unstable.shared_sort_unstable_by(|a, b| a.cmp(b));
        let mut expected = keys;
        expected.sort_unstable();
        assert_eq!(unstable, expected);
    }
}
