//! Runs advanced together, window by window of simulated time, so that
//! the first of them to fail ends the others soon after instead of
//! leaving them to run to the end.
//!
//! Compile's verification asks of a set of plants only which one first
//! strays over the bound, where and why (`plants::run_each_in_step`): the
//! station is re-timed there and the set run again. Run one after
//! another, every plant that passes a failing station runs its whole
//! length for nothing. Here each run, at every window boundary, waits
//! until every other run of the group has reached that boundary or
//! ended; it then ends if some run has already failed at or before the
//! boundary. A run failing at t ≤ b ends before it could reach b, and no
//! run passes b before every run has reached b, so the set of failures
//! known at boundary b is exactly those at or before b whatever the
//! threads' timing: which runs end where is the same on every machine,
//! and so is every report.

use std::sync::{Condvar, Mutex, PoisonError};

/// A group of runs in step.
pub(super) struct Group {
    state: Mutex<State>,
    moved: Condvar,
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
        }
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
        }
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
}

impl Gate<'_> {
    /// At boundary `t_s`: wait until every run of the group has reached it
    /// or ended; false (the run ends here) when one failed at or before it.
    pub(super) fn go_on(&mut self, t_s: f64) -> bool {
        let g = self.group;
        let mut s = g.state.lock().unwrap_or_else(PoisonError::into_inner);
        s.at[self.index] = t_s;
        g.moved.notify_all();
        while s.at.iter().any(|&a| a < t_s) {
            s = g.moved.wait(s).unwrap_or_else(PoisonError::into_inner);
        }
        let go = !s.failed_at.is_some_and(|f| f <= t_s);
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

    /// Runs of different lengths failing at set times, on threads: each
    /// ends at the first boundary at or after the earliest failure, or at
    /// its own failure or end if sooner, whatever the threads' timing.
    #[test]
    fn runs_end_at_the_first_boundary_after_the_first_failure() {
        // (ends at, fails at): boundaries every 1.0
        let runs = [
            (10.0, None),
            (10.0, Some(3.5)),
            (2.5, None),
            (10.0, Some(6.2)),
        ];
        for _ in 0..20 {
            let group = Group::new(runs.len());
            let ended: Vec<f64> = std::thread::scope(|sc| {
                let handles: Vec<_> = runs
                    .iter()
                    .enumerate()
                    .map(|(i, &(end, fail))| {
                        let group = &group;
                        sc.spawn(move || {
                            let mut gate = group.gate(i);
                            let mut t = 0.0;
                            loop {
                                // one window of "work"
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
                                if !gate.go_on(t) {
                                    return t;
                                }
                            }
                        })
                    })
                    .collect();
                handles.into_iter().map(|h| h.join().unwrap()).collect()
            });
            assert_eq!(ended, vec![4.0, 3.5, 2.5, 4.0]);
        }
    }
}
