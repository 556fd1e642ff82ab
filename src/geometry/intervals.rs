//! Sets of intervals on a line: sorted, disjoint `(start, end)` pairs, as the pieces of a line
//! inside a polygon come from [`SweepFrame::clip_each`](super::SweepFrame::clip_each). Union,
//! intersection and difference by one merge of the two lists.

/// The pieces of a line: sorted, disjoint intervals `(start, end)` with `start < end`.
pub type Intervals = Vec<(f64, f64)>;

/// Where `a` or `b` holds.
///
/// ```
/// use furrow::geometry::intervals::union;
/// assert_eq!(union(&[(0., 2.), (5., 6.)], &[(1., 3.)]), vec![(0., 3.), (5., 6.)]);
/// ```
pub fn union(a: &[(f64, f64)], b: &[(f64, f64)]) -> Intervals {
    let mut all: Vec<(f64, f64)> = Vec::with_capacity(a.len() + b.len());
    let (mut i, mut j) = (0, 0);
    while i < a.len() || j < b.len() {
        let take_a = j >= b.len() || (i < a.len() && a[i].0 <= b[j].0);
        let next = if take_a { a[i] } else { b[j] };
        if take_a {
            i += 1;
        } else {
            j += 1;
        }
        match all.last_mut() {
            Some(last) if next.0 <= last.1 => {
                if next.1 > last.1 {
                    last.1 = next.1;
                }
            }
            _ => all.push(next),
        }
    }
    all
}

/// Where both `a` and `b` hold.
///
/// ```
/// use furrow::geometry::intervals::intersection;
/// assert_eq!(intersection(&[(0., 4.), (5., 9.)], &[(3., 6.)]), vec![(3., 4.), (5., 6.)]);
/// ```
pub fn intersection(a: &[(f64, f64)], b: &[(f64, f64)]) -> Intervals {
    let mut out = Vec::new();
    let (mut i, mut j) = (0, 0);
    while let (Some(&(a0, a1)), Some(&(b0, b1))) = (a.get(i), b.get(j)) {
        let (lo, hi) = (if a0 > b0 { a0 } else { b0 }, if a1 < b1 { a1 } else { b1 });
        if hi > lo {
            out.push((lo, hi));
        }
        if a1 < b1 {
            i += 1;
        } else {
            j += 1;
        }
    }
    out
}

/// Where `a` holds and `b` does not.
///
/// ```
/// use furrow::geometry::intervals::difference;
/// assert_eq!(difference(&[(0., 10.)], &[(2., 3.), (8., 12.)]), vec![(0., 2.), (3., 8.)]);
/// ```
pub fn difference(a: &[(f64, f64)], b: &[(f64, f64)]) -> Intervals {
    let mut out = Vec::new();
    let mut j = 0;
    for &(a0, a1) in a {
        let mut start = a0;
        while j < b.len() && b[j].1 <= start {
            j += 1;
        }
        let mut k = j;
        while let Some(&(b0, b1)) = b.get(k) {
            if b0 >= a1 {
                break;
            }
            if b0 > start {
                out.push((start, b0));
            }
            if b1 > start {
                start = b1;
            }
            k += 1;
        }
        if a1 > start {
            out.push((start, a1));
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Whether `x` is in the set.
    fn holds(set: &[(f64, f64)], x: f64) -> bool {
        set.iter().any(|&(a, b)| a < x && x < b)
    }

    #[test]
    fn the_operations_agree_with_membership_point_by_point() {
        let sets: [&[(f64, f64)]; 5] = [
            &[],
            &[(0.0, 10.0)],
            &[(1.0, 2.0), (3.0, 4.0), (6.5, 9.0)],
            &[(-5.0, 1.5), (2.0, 3.5), (8.0, 20.0)],
            &[(3.0, 4.0)],
        ];
        for a in sets {
            for b in sets {
                let (u, i, d) = (union(a, b), intersection(a, b), difference(a, b));
                for set in [&u, &i, &d] {
                    assert!(set.windows(2).all(|w| w[0].1 <= w[1].0), "{set:?}");
                    assert!(set.iter().all(|p| p.0 < p.1), "{set:?}");
                }
                for k in -60..=220 {
                    let x = k as f64 * 0.1 + 0.013;
                    assert_eq!(holds(&u, x), holds(a, x) || holds(b, x));
                    assert_eq!(holds(&i, x), holds(a, x) && holds(b, x));
                    assert_eq!(holds(&d, x), holds(a, x) && !holds(b, x));
                }
            }
        }
    }
}
