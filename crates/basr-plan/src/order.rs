//! Stroke order and direction that minimise air travel.
//!
//! The problem is an open travelling-salesman tour over items that may be
//! run either way (a stroke, or one pass of a wide stroke, painted from
//! either end), as pen-plotter path optimisers solve it: a greedy
//! nearest-neighbour tour, then 2-opt (reverse a run of items, flipping
//! each) and or-opt (move a run of 1–3 items elsewhere, either way round)
//! until no move gains. The cost of an air move is given by the caller (the
//! compile pipeline passes an estimate of the arm's air-move time) and must
//! be symmetric. Everything is deterministic: ties go to the lower index.

/// The two ends of one item, in its natural direction.
/// `P` is what the cost compares: a road point, or a point with the
/// fan's direction and tilt there.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Ends<P = [f64; 2]> {
    pub start: P,
    pub end: P,
}

/// One step of the tour: which item, and whether it runs end → start.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Visit {
    pub item: usize,
    pub reversed: bool,
}

impl Visit {
    fn entry<P: Copy>(&self, items: &[Ends<P>]) -> P {
        let e = items[self.item];
        if self.reversed {
            e.end
        } else {
            e.start
        }
    }
    fn exit<P: Copy>(&self, items: &[Ends<P>]) -> P {
        let e = items[self.item];
        if self.reversed {
            e.start
        } else {
            e.end
        }
    }
    fn flipped(self) -> Visit {
        Visit {
            item: self.item,
            reversed: !self.reversed,
        }
    }
}

/// Euclidean distance: the plain air-travel cost.
pub fn distance(a: [f64; 2], b: [f64; 2]) -> f64 {
    (a[0] - b[0]).hypot(a[1] - b[1])
}

/// Total air cost of a tour starting at `from` (not returning).
pub fn tour_cost<P: Copy>(
    items: &[Ends<P>],
    tour: &[Visit],
    from: P,
    cost: &impl Fn(P, P) -> f64,
) -> f64 {
    let mut at = from;
    let mut total = 0.0;
    for v in tour {
        total += cost(at, v.entry(items));
        at = v.exit(items);
    }
    total
}

/// Gains smaller than this are ignored, so rounding cannot make the
/// improvement loop cycle.
const MIN_GAIN: f64 = 1e-9;
/// Upper bound on improvement sweeps (each strictly lowers the cost; the
/// bound only guards against pathological cost functions).
const MAX_SWEEPS: usize = 200;

/// The caller's cost between every pair of points the tour can join: the
/// start (node 0) and both ends of every item (item i's start is node
/// 2i + 1, its end 2i + 2). Each pair is priced once; the searches then
/// look costs up instead of calling the cost (the compile pipeline's is an
/// arm-time estimate with trigonometry). The figures are the caller's own,
/// added in the same order as before, so the tour is the same bit for bit.
struct Table {
    n: usize,
    cost: Vec<f64>,
}

impl Table {
    fn new<P: Copy>(items: &[Ends<P>], from: P, cost: &impl Fn(P, P) -> f64) -> Table {
        let mut pts = Vec::with_capacity(2 * items.len() + 1);
        pts.push(from);
        for e in items {
            pts.push(e.start);
            pts.push(e.end);
        }
        let n = pts.len();
        let mut c = Vec::with_capacity(n * n);
        for &a in &pts {
            for &b in &pts {
                c.push(cost(a, b));
            }
        }
        Table { n, cost: c }
    }

    fn get(&self, a: usize, b: usize) -> f64 {
        self.cost[a * self.n + b]
    }

    /// Summed air cost of a tour from node 0, in tour order.
    fn tour<'a>(&self, tour: impl IntoIterator<Item = &'a Visit>) -> f64 {
        let mut at = 0;
        let mut total = 0.0;
        for v in tour {
            total += self.get(at, v.entry_node());
            at = v.exit_node();
        }
        total
    }
}

impl Visit {
    fn entry_node(&self) -> usize {
        2 * self.item + if self.reversed { 2 } else { 1 }
    }
    fn exit_node(&self) -> usize {
        2 * self.item + if self.reversed { 1 } else { 2 }
    }
}

/// Order and direction of `items` starting from `from`, minimising the summed
/// `cost` of the air moves between them. `cost` must be symmetric.
pub fn order<P: Copy>(items: &[Ends<P>], from: P, cost: impl Fn(P, P) -> f64) -> Vec<Visit> {
    let t = Table::new(items, from, &cost);
    let mut tour = greedy_in(&t, items.len());
    for _ in 0..MAX_SWEEPS {
        let a = two_opt(&t, &mut tour);
        let b = or_opt(&t, &mut tour);
        if !(a || b) {
            break;
        }
    }
    tour
}

/// The nearest-neighbour tour alone (the improvement's starting point).
#[cfg(test)]
fn greedy(items: &[Ends], from: [f64; 2], cost: &impl Fn([f64; 2], [f64; 2]) -> f64) -> Vec<Visit> {
    greedy_in(&Table::new(items, from, cost), items.len())
}

fn greedy_in(t: &Table, n: usize) -> Vec<Visit> {
    let mut used = vec![false; n];
    let mut tour = Vec::with_capacity(n);
    let mut at = 0;
    for _ in 0..n {
        let mut best: Option<(f64, Visit)> = None;
        for i in (0..n).filter(|&i| !used[i]) {
            for reversed in [false, true] {
                let v = Visit { item: i, reversed };
                let c = t.get(at, v.entry_node());
                if best.is_none_or(|(b, _)| c < b - MIN_GAIN) {
                    best = Some((c, v));
                }
            }
        }
        if let Some((_, v)) = best {
            used[v.item] = true;
            at = v.exit_node();
            tour.push(v);
        }
    }
    tour
}

/// Exit node before position `i` of the tour (the start for i = 0).
fn exit_before(tour: &[Visit], i: usize) -> usize {
    if i == 0 {
        0
    } else {
        tour[i - 1].exit_node()
    }
}

/// One sweep of 2-opt: reverse tour[i..=j] (flipping each item) when it
/// shortens the tour. Returns whether anything changed.
fn two_opt(t: &Table, tour: &mut [Visit]) -> bool {
    let n = tour.len();
    let mut changed = false;
    for i in 0..n {
        for j in i..n {
            let before = exit_before(tour, i);
            let first_in = tour[i].entry_node();
            let last_out = tour[j].exit_node();
            let next = (j + 1 < n).then(|| tour[j + 1].entry_node());
            let old = t.get(before, first_in) + next.map_or(0.0, |x| t.get(last_out, x));
            // Reversed run: enters at the old last item's exit, leaves at
            // the old first item's entry.
            let new = t.get(before, last_out) + next.map_or(0.0, |x| t.get(first_in, x));
            if new < old - MIN_GAIN {
                tour[i..=j].reverse();
                for v in &mut tour[i..=j] {
                    *v = v.flipped();
                }
                changed = true;
            }
        }
    }
    changed
}

/// One sweep of or-opt: move a run of 1–3 items to another place, either
/// way round, when that shortens the tour.
fn or_opt(t: &Table, tour: &mut Vec<Visit>) -> bool {
    let mut changed = false;
    for len in 1..=3usize {
        let mut i = 0;
        while i + len <= tour.len() {
            let base = t.tour(tour.iter());
            let run = &tour[i..i + len];
            let flipped: Vec<Visit> = run.iter().rev().map(|v| v.flipped()).collect();
            // The tour without the run, and that tour with the run put back
            // at position `at` (either way round), walked without copying.
            let rest = || tour[..i].iter().chain(&tour[i + len..]);
            let m = tour.len() - len;
            let mut best: Option<(f64, usize, bool)> = None;
            for at in 0..=m {
                if at == i {
                    continue; // the same place
                }
                for rev in [false, true] {
                    let put = if rev { &flipped[..] } else { run };
                    let c = t.tour(rest().take(at).chain(put).chain(rest().skip(at)));
                    if c < base - MIN_GAIN && best.is_none_or(|(b, _, _)| c < b - MIN_GAIN) {
                        best = Some((c, at, rev));
                    }
                }
            }
            if let Some((_, at, rev)) = best {
                let put: Vec<Visit> = if rev { flipped } else { run.to_vec() };
                let mut cand: Vec<Visit> = rest().take(at).copied().collect();
                cand.extend_from_slice(&put);
                cand.extend(rest().skip(at).copied());
                *tour = cand;
                changed = true;
            }
            i += 1;
        }
    }
    changed
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    fn seg(x0: f64, y0: f64, x1: f64, y1: f64) -> Ends {
        Ends {
            start: [x0, y0],
            end: [x1, y1],
        }
    }

    fn is_permutation(tour: &[Visit], n: usize) -> bool {
        let mut seen = vec![false; n];
        for v in tour {
            if v.item >= n || seen[v.item] {
                return false;
            }
            seen[v.item] = true;
        }
        tour.len() == n
    }

    #[test]
    fn flips_a_stroke_to_avoid_the_long_way_round() {
        // Three vertical bars; the best tour snakes: up, down, up.
        let items = [
            seg(0.0, 0.0, 0.0, 1.0),
            seg(1.0, 0.0, 1.0, 1.0),
            seg(2.0, 0.0, 2.0, 1.0),
        ];
        let t = order(&items, [0.0, 0.0], distance);
        assert_eq!(
            t,
            vec![
                Visit {
                    item: 0,
                    reversed: false
                },
                Visit {
                    item: 1,
                    reversed: true
                },
                Visit {
                    item: 2,
                    reversed: false
                },
            ]
        );
        assert!((tour_cost(&items, &t, [0.0, 0.0], &distance) - 2.0).abs() < 1e-12);
    }

    #[test]
    fn improvement_beats_greedy_trap() {
        // Greedy from the origin takes the near item at x = 1, then must go
        // back past the origin; 2-opt/or-opt fix the order.
        let items = [
            seg(1.0, 0.0, 1.1, 0.0),
            seg(-1.0, 0.0, -1.1, 0.0),
            seg(-3.0, 0.0, -3.1, 0.0),
            seg(3.0, 0.0, 3.1, 0.0),
        ];
        let g = greedy(&items, [0.0, 0.0], &distance);
        let t = order(&items, [0.0, 0.0], distance);
        let (cg, ct) = (
            tour_cost(&items, &g, [0.0, 0.0], &distance),
            tour_cost(&items, &t, [0.0, 0.0], &distance),
        );
        assert!(ct <= cg + 1e-12, "{ct} > {cg}");
        assert!(is_permutation(&t, items.len()));
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(64))]
        #[test]
        fn never_worse_than_greedy_and_deterministic(
            pts in proptest::collection::vec((-5.0f64..5.0, -5.0f64..5.0, -5.0f64..5.0, -5.0f64..5.0), 0..14)
        ) {
            let items: Vec<Ends> = pts.iter().map(|&(a, b, c, d)| seg(a, b, c, d)).collect();
            let g = greedy(&items, [0.0, 0.0], &distance);
            let t = order(&items, [0.0, 0.0], distance);
            prop_assert!(is_permutation(&t, items.len()));
            let cg = tour_cost(&items, &g, [0.0, 0.0], &distance);
            let ct = tour_cost(&items, &t, [0.0, 0.0], &distance);
            prop_assert!(ct <= cg + 1e-9);
            prop_assert_eq!(t, order(&items, [0.0, 0.0], distance));
        }
    }
}
