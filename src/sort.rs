//! Sorting with one copy of the standard library's sort for the whole crate.
//!
//! `slice::sort_by` is generic over its element type and its comparator, so every call with a
//! closure of its own compiles a sort of its own (driftsort or quicksort with their small-sort
//! networks, 10 to 25 KB of WebAssembly each). Through [`SharedSort`] the comparator is passed
//! as a `dyn` reference, and a slice of more than 20 elements is sorted through the positions
//! of its elements (`usize`, by one stable and one unstable sort for the crate), then put in
//! that order in place; shorter slices are sorted by insertion, a few hundred bytes per element
//! type. The stable sorts give exactly the order of `slice::sort_by`; the unstable one may
//! order equal elements otherwise than `slice::sort_unstable_by` (neither says how).
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
    /// As `sort_by(|a, b| key(a).total_cmp(&key(b)))` (stable), with the keys computed once
    /// and sorted directly: for the long sorts of a sweep.
    fn shared_sort_by_float_key(&mut self, key: impl FnMut(&T) -> f64);
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

    fn shared_sort_by_float_key(&mut self, mut key: impl FnMut(&T) -> f64) {
        if self.len() <= INSERTION_MAX {
            insertion_sort(self, &mut |a, b| key(a).total_cmp(&key(b)));
            return;
        }
        let mut keyed: Vec<(f64, usize)> = self.iter().map(&mut key).zip(0..).collect();
        sort_keyed(&mut keyed);
        let mut order: Vec<usize> = keyed.into_iter().map(|(_, i)| i).collect();
        permute(self, &mut order);
    }
}

/// Sorts numbers ascending by [`f64::total_cmp`]: by insertion when short (the crossings of a
/// line), else by the sort of keys with positions that [`SharedSort::shared_sort_by_float_key`]
/// uses, without the indirect calls of [`SharedSort`]. Numbers equal by `total_cmp` have the same
/// bits: the order is that of a stable sort.
///
/// ```
/// let mut v = [2.5, -0.0, 0.0, -3.0];
/// furrow::sort::sort_floats(&mut v);
/// assert_eq!(v.map(f64::to_bits), [-3.0, -0.0, 0.0, 2.5].map(f64::to_bits));
/// ```
pub fn sort_floats(v: &mut [f64]) {
    if v.len() <= INSERTION_MAX {
        for i in 1..v.len() {
            let x = v[i];
            let mut k = i;
            while k > 0 && v[k - 1].total_cmp(&x) == Ordering::Greater {
                v[k] = v[k - 1];
                k -= 1;
            }
            v[k] = x;
        }
        return;
    }
    // Through the keyed sort: one sort of numbers in the module, not two.
    let mut keyed: Vec<(f64, usize)> = v.iter().copied().zip(0..).collect();
    sort_keyed(&mut keyed);
    for (x, (k, _)) in v.iter_mut().zip(keyed) {
        *x = k;
    }
}

/// Keys with their positions, by key and then position: the order of a stable sort by key.
#[inline(never)]
fn sort_keyed(keyed: &mut [(f64, usize)]) {
    keyed.sort_unstable_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
}

/// Up to this many elements a slice is sorted in place by insertion (a few hundred bytes of
/// code per element type); longer ones through their positions, by the crate's one sort.
const INSERTION_MAX: usize = 20;

fn stable<T>(v: &mut [T], compare: &mut dyn FnMut(&T, &T) -> Ordering) {
    through_positions(v, compare, sort_positions);
}

fn unstable<T>(v: &mut [T], compare: &mut dyn FnMut(&T, &T) -> Ordering) {
    through_positions(v, compare, sort_positions_unstable);
}

/// Sorts `v` by insertion when short, else its positions by `sort`, then puts the elements in
/// that order.
fn through_positions<T>(
    v: &mut [T],
    compare: &mut dyn FnMut(&T, &T) -> Ordering,
    sort: fn(&mut [usize], &mut dyn FnMut(usize, usize) -> Ordering),
) {
    if v.len() <= INSERTION_MAX {
        insertion_sort(v, compare);
        return;
    }
    let mut order: Vec<usize> = (0..v.len()).collect();
    sort(&mut order, &mut |i, j| compare(&v[i], &v[j]));
    permute(v, &mut order);
}

/// Stable: each element moves left past those greater than it.
fn insertion_sort<T>(v: &mut [T], compare: &mut dyn FnMut(&T, &T) -> Ordering) {
    for i in 1..v.len() {
        let mut k = i;
        while k > 0 && compare(&v[k - 1], &v[k]) == Ordering::Greater {
            v.swap(k - 1, k);
            k -= 1;
        }
    }
}

/// The one stable sort of the crate: positions, by what their elements compare.
#[inline(never)]
fn sort_positions(order: &mut [usize], compare: &mut dyn FnMut(usize, usize) -> Ordering) {
    order.sort_by(|&a, &b| compare(a, b));
}

/// The one unstable sort of the crate.
#[inline(never)]
fn sort_positions_unstable(order: &mut [usize], compare: &mut dyn FnMut(usize, usize) -> Ordering) {
    order.sort_unstable_by(|&a, &b| compare(a, b));
}

/// Rearranges `v` so that its element `k` is the one that was at `order[k]`, in place, by
/// following the permutation's cycles (`order` is left as the identity).
fn permute<T>(v: &mut [T], order: &mut [usize]) {
    for start in 0..order.len() {
        let mut k = start;
        loop {
            let from = order[k];
            order[k] = k;
            if from == start || from == k {
                break;
            }
            v.swap(k, from);
            k = from;
        }
    }
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

    #[test]
    fn short_and_long_slices_with_ties_keep_the_stable_order() {
        for n in [0, 1, 2, 5, INSERTION_MAX, INSERTION_MAX + 1, 64, 333] {
            // Keys with many ties, and a payload that tells equal keys apart.
            let items: Vec<(u32, String)> = (0..n as u32)
                .map(|i| ((i * 7919) % 5, format!("item {i}")))
                .collect();
            let mut ours = items.clone();
            ours.shared_sort_by(|a, b| a.0.cmp(&b.0));
            let mut expected = items.clone();
            expected.sort_by_key(|a| a.0);
            assert_eq!(ours, expected, "{n} elements");
            let mut descending = items.clone();
            descending.shared_sort_unstable_by(|a, b| b.cmp(a));
            let mut expected = items;
            expected.sort_unstable_by(|a, b| b.cmp(a));
            assert_eq!(descending, expected, "{n} elements, unstable (no ties)");
        }
    }

    #[test]
    fn float_keys_sort_as_a_stable_sort_by_total_cmp() {
        for n in [3, INSERTION_MAX, INSERTION_MAX + 1, 100] {
            let items: Vec<(f64, usize)> =
                (0..n).map(|i| (((i * 37) % 7) as f64 - 3.0, i)).collect();
            let mut ours = items.clone();
            ours.shared_sort_by_float_key(|x| x.0);
            let mut expected = items;
            expected.sort_by(|a, b| a.0.total_cmp(&b.0));
            assert_eq!(ours, expected, "{n} elements");
        }
        for n in [0, 1, 7, INSERTION_MAX, INSERTION_MAX + 1, 50] {
            let mut floats: Vec<f64> = (0..n)
                .map(|i| match i % 9 {
                    4 => -0.0,
                    7 => 0.0,
                    _ => ((i * 13) % 11) as f64 * 0.5 - 2.0,
                })
                .collect();
            let mut expected = floats.clone();
            expected.sort_by(f64::total_cmp);
            sort_floats(&mut floats);
            let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
            assert_eq!(bits(&floats), bits(&expected), "{n} numbers");
        }
    }

    #[test]
    fn permuting_follows_every_cycle() {
        let mut v = vec!['a', 'b', 'c', 'd', 'e', 'f'];
        // Element k becomes the one at order[k]: cycles (0 3 5), (1 2) and the fixed point 4.
        let mut order = vec![3, 2, 1, 5, 4, 0];
        permute(&mut v, &mut order);
        assert_eq!(v, ['d', 'c', 'b', 'f', 'e', 'a']);
        assert_eq!(order, [0, 1, 2, 3, 4, 5]);
    }
}
