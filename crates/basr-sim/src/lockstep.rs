//! Runs advanced together, window by window of simulated time, so that
//! the first of them to fail ends the others soon after instead of
//! leaving them to run to the end.
//!
//! Compile's verification asks of a set of plants only which one first
//! strays over the bound, where and why (`plants::run_each_in_step`): the
//! station is re-timed there and the set run again. Run one after
//! another, every plant that passes a failing station runs its whole
//! length for nothing. Here each run, at every window boundary b (before
//! it simulates the tick at b), waits until every other run of the group
//! has reached b or ended; it then ends if some run has already failed
//! before b. A run failing at t < b ends before it reaches b, a run
//! failing at b or later has reached b first, and no run passes b before
//! every run has reached it: the failures known at boundary b are exactly
//! those before b whatever the threads' timing, so which runs end where is
//! the same on every machine, and so is every report.

use std::sync::{Condvar, Mutex, PoisonError};

/// A group of runs in step.
pub(super) struct Group {
    state: Mutex<State>,
    moved: Condvar,
    /// How far (s) the leader may run ahead of the slowest other run
    /// (`leading_by`); unbounded unless set.
    lead_s: f64,
}

struct State {
    /// Each run's position (s): the boundary it waits at or last passed,
    /// −∞ before it starts, +∞ once it ended.
    at: Vec<f64>,
    /// The earliest failure among the runs that ended at one (s).
    failed_at: Option<f64>,
}

impl Group {
    /// A group of `n` runs, none started.
    pub(super) fn new(n: usize) -> Group {
        Group {
            state: Mutex::new(State {
                at: vec![f64::NEG_INFINITY; n],
                failed_at: None,
            }),
            moved: Condvar::new(),
            lead_s: f64::INFINITY,
        }
    }

    /// The group with its leader held to at most `lead_s` ahead of the
    /// slowest other run still going ([`Gate::go_on`]): a leader on a core
    /// of its own while the others share the rest runs far ahead of them,
    /// and all of that is lost when one of them then fails early (a
    /// fitted STOP's description ran 88 s of simulated time while the
    /// plant set reached its failure at 24 s). Held, it runs no further
    /// than `lead_s` past the boundary after that failure, and the others
    /// still never wait for it longer than they would.
    pub(super) fn leading_by(self, lead_s: f64) -> Group {
        Group { lead_s, ..self }
    }

    /// Run `index`'s gate (the others wait for it at each boundary from
    /// now until it reaches that boundary or leaves): it leaves the group
    /// when dropped, whatever ends the run (a panic included), so no other
    /// run waits for it forever.
    pub(super) fn gate(&self, index: usize) -> Gate<'_> {
        Gate {
            group: self,
            index,
            stopped: false,
            failed_at: None,
            left: false,
            leader: false,
        }
    }

    /// Run `index`'s gate as the group's leader: the others wait for it at
    /// each boundary and its failure ends them, but it waits for none: it
    /// ends at the first boundary where it already knows of an earlier
    /// failure of the others, which depends on the threads' timing
    /// (compile's run of the robot description beside the plant set: a
    /// run on from its last checkpoint is the run it would have made, and
    /// the plants, which wait, end where they would).
    pub(super) fn leader_gate(&self, index: usize) -> Gate<'_> {
        // Not `Gate { leader: true, ..self.gate(index) }`: the temporary
        // gate that spells would be dropped, and a dropped gate leaves the
        // group, so the others would not wait for the leader.
        let mut g = self.gate(index);
        g.leader = true;
        g
    }

    /// Every run's gate, run `leader`'s the leader's, made together before
    /// any run starts: a spawn that fails drops the gates not yet handed
    /// over, so no run waits for one that never started.
    pub(super) fn gates(&self, leader: Option<usize>) -> Vec<Gate<'_>> {
        let n = self
            .state
            .lock()
            .unwrap_or_else(PoisonError::into_inner)
            .at
            .len();
        (0..n)
            .map(|i| {
                if leader == Some(i) {
                    self.leader_gate(i)
                } else {
                    self.gate(i)
                }
            })
            .collect()
    }

    fn update(&self, f: impl FnOnce(&mut State)) {
        let mut s = self.state.lock().unwrap_or_else(PoisonError::into_inner);
        f(&mut s);
        drop(s);
        self.moved.notify_all();
    }
}

/// One run's place in its group.
pub(super) struct Gate<'a> {
    group: &'a Group,
    index: usize,
    /// The group ended this run at a boundary.
    pub(super) stopped: bool,
    /// Where this run failed (its first painting error over the bound).
    failed_at: Option<f64>,
    left: bool,
    /// This run waits for none of the others (`Group::leader_gate`).
    leader: bool,
}

impl Gate<'_> {
    /// At boundary `t_s` (before its tick): wait until every run of the
    /// group has reached it or ended; false (the run ends here) when one
    /// failed before it.
    pub(super) fn go_on(&mut self, t_s: f64) -> bool {
        let g = self.group;
        let mut s = g.state.lock().unwrap_or_else(PoisonError::into_inner);
        s.at[self.index] = t_s;
        g.moved.notify_all();
        // The leader runs on: the others wait for it at each boundary, so
        // they still know of its failures before it, and no core waits for
        // the slowest of the others while the leader has work, up to its
        // lead (`Group::leading_by`). It ends once it knows the others
        // failed before here.
        if self.leader {
            let behind = t_s - g.lead_s;
            let failed = |s: &State| s.failed_at.is_some_and(|f| f < t_s);
            while !failed(&s) && s.at.iter().any(|&a| a < behind) {
                s = g.moved.wait(s).unwrap_or_else(PoisonError::into_inner);
            }
            let go = !failed(&s);
            self.stopped = !go;
            return go;
        }
        while s.at.iter().any(|&a| a < t_s) {
            s = g.moved.wait(s).unwrap_or_else(PoisonError::into_inner);
        }
        let go = !s.failed_at.is_some_and(|f| f < t_s);
        self.stopped = !go;
        go
    }

    /// The run failed at `t_s` and ends there.
    pub(super) fn failed(&mut self, t_s: f64) {
        self.failed_at = Some(t_s);
    }

    /// The run ended: the others no longer wait for it (and learn where it
    /// failed). Once; dropping the gate does it otherwise.
    pub(super) fn leave(&mut self) {
        if std::mem::replace(&mut self.left, true) {
            return;
        }
        let (index, failed) = (self.index, self.failed_at);
        self.group.update(|s| {
            s.at[index] = f64::INFINITY;
            if let Some(t) = failed {
                s.failed_at = Some(s.failed_at.map_or(t, |f| f.min(t)));
            }
        });
    }
}

impl Drop for Gate<'_> {
    fn drop(&mut self) {
        self.leave();
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Runs in `run_resumable`'s order (at each boundary: wait, then the
    /// window's ticks, the first at the boundary itself), failing at set
    /// times, on threads: each ends at the first boundary after the
    /// earliest failure, or at its own failure or end if sooner, whatever
    /// the threads' timing; a failure on a boundary is seen at the next.
    #[test]
    fn runs_end_at_the_first_boundary_after_the_first_failure() {
        // (ends at, fails at): boundaries every 1.0
        type Case = (&'static [(f64, Option<f64>)], &'static [f64]);
        let cases: [Case; 2] = [
            (
                &[
                    (10.0, None),
                    (10.0, Some(3.5)),
                    (2.5, None),
                    (10.0, Some(6.2)),
                ],
                &[4.0, 3.5, 2.5, 4.0],
            ),
            // failing on the boundary at 4 (its tick at 4 runs after the
            // others may have passed 4): all end at 5
            (
                &[(10.0, Some(4.0)), (10.0, None), (10.0, Some(4.5))],
                &[4.0, 5.0, 4.5],
            ),
        ];
        for (runs, want) in cases {
            for _ in 0..20 {
                assert_eq!(ended(runs, None), want.to_vec(), "{runs:?}");
            }
        }
    }

    /// The leader (run 0) ends the others at the boundary after its
    /// failure; theirs end it at a boundary after it knows of them (at
    /// the latest its end: it does not wait to know).
    #[test]
    fn the_leader_ends_the_others_and_ends_once_it_knows_of_theirs() {
        type Case = (&'static [(f64, Option<f64>)], &'static [f64]);
        let cases: [Case; 1] = [
            // the leader fails first: the others end at 4
            (
                &[(10.0, Some(3.5)), (10.0, None), (10.0, Some(6.2))],
                &[3.5, 4.0, 4.0],
            ),
        ];
        for (runs, want) in cases {
            for _ in 0..20 {
                assert_eq!(ended(runs, Some(0)), want.to_vec(), "{runs:?}");
            }
        }
        // a plant fails first: the others end at 3, the leader at a
        // boundary from 3 on, or at its own end or failure if sooner
        let cases: [Case; 2] = [
            (
                &[(10.0, None), (10.0, Some(2.5)), (10.0, None)],
                &[10.0, 2.5, 3.0],
            ),
            (
                &[(10.0, Some(7.5)), (10.0, Some(2.5)), (10.0, None)],
                &[7.5, 2.5, 3.0],
            ),
        ];
        for (runs, most) in cases {
            for _ in 0..20 {
                let got = ended(runs, Some(0));
                assert_eq!(got[1..], most[1..], "{runs:?}");
                let leader = got[0];
                assert!(
                    leader <= most[0]
                        && (leader == most[0] || leader.fract() == 0.0 && leader >= 3.0),
                    "{runs:?}: the leader ended at {leader}"
                );
            }
        }
    }

    /// A leader held to a lead ends no later than that lead past the
    /// boundary after the others' first failure, however far ahead the
    /// threads' timing would let it run.
    #[test]
    fn a_held_leader_ends_within_its_lead_of_the_first_failure() {
        let runs: &[(f64, Option<f64>)] = &[(40.0, None), (40.0, Some(2.5)), (40.0, None)];
        for _ in 0..20 {
            let got = ended_leading(runs, Some(0), 2.0);
            assert_eq!(got[1..], [2.5, 3.0], "the others end as without a lead");
            assert!(
                got[0] >= 3.0 && got[0] <= 5.0,
                "the leader ended at {}, not within 2 of boundary 3",
                got[0]
            );
        }
        // without a failure the lead changes nothing: every run ends at its end
        let runs: &[(f64, Option<f64>)] = &[(12.0, None), (10.5, None), (12.0, Some(11.5))];
        assert_eq!(ended_leading(runs, Some(0), 2.0), [12.0, 10.5, 11.5]);
    }

    /// Making the leader's gate leaves it in the group: the others wait for
    /// it until it reaches a boundary or leaves.
    #[test]
    fn a_leader_gate_is_in_its_group_until_it_leaves() {
        let group = Group::new(2);
        let mut gates = group.gates(Some(0));
        let at = |g: &Group| g.state.lock().unwrap().at.clone();
        assert_eq!(at(&group), vec![f64::NEG_INFINITY; 2]);
        gates[0].leave();
        assert_eq!(at(&group)[0], f64::INFINITY);
        assert_eq!(at(&group)[1], f64::NEG_INFINITY);
    }

    /// Where each run of `runs` (end, failure) ends, in step on threads,
    /// run `leader` with the leader's gate.
    fn ended(runs: &[(f64, Option<f64>)], leader: Option<usize>) -> Vec<f64> {
        ended_leading(runs, leader, f64::INFINITY)
    }

    /// [`ended`] with the leader held to `lead_s` (`Group::leading_by`).
    fn ended_leading(runs: &[(f64, Option<f64>)], leader: Option<usize>, lead_s: f64) -> Vec<f64> {
        let group = Group::new(runs.len()).leading_by(lead_s);
        let gates = group.gates(leader);
        std::thread::scope(|sc| {
            let handles: Vec<_> = runs
                .iter()
                .zip(gates)
                .map(|(&(end, fail), mut gate)| {
                    sc.spawn(move || {
                        let mut t: f64 = 0.0;
                        loop {
                            if t > 0.0 && !gate.go_on(t) {
                                return t;
                            }
                            // the window's ticks, from t on
                            std::thread::yield_now();
                            let next = t + 1.0;
                            if let Some(f) = fail.filter(|&f| f < next) {
                                gate.failed(f);
                                return f;
                            }
                            if end < next {
                                return end;
                            }
                            t = next;
                        }
                    })
                })
                .collect();
            handles.into_iter().map(|h| h.join().unwrap()).collect()
        })
    }
}
