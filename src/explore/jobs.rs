//! Scheduling of the page's computations, apart from what they compute:
//! a newer request of the same client and channel supersedes an older one
//! ([`Latest`]), at most [`Slots`] computations run at once, and each runs
//! under a [`Budget`] of time and leaves. The three meet only in
//! [`Ticket`], which a computation's progress callback consults.

use std::collections::HashMap;
use std::ops::ControlFlow;
use std::sync::{Condvar, Mutex};
use std::time::{Duration, Instant};

/// The newest sequence number seen per `(client, channel)`.
#[derive(Default)]
pub struct Latest {
    seen: Mutex<HashMap<String, u64>>,
}

impl Latest {
    /// Records `seq` for `key`; false when a newer one was already seen
    /// (the request is stale on arrival).
    pub fn arrive(&self, key: &str, seq: u64) -> bool {
        let mut seen = self.seen.lock().unwrap_or_else(|e| e.into_inner());
        // Bounded: a page makes a handful of keys; forget them all if a
        // misbehaving client makes many.
        if seen.len() > 4096 {
            seen.clear();
        }
        let e = seen.entry(key.to_string()).or_insert(seq);
        if seq < *e {
            return false;
        }
        *e = seq;
        true
    }

    /// Whether a request newer than `seq` has arrived for `key`.
    pub fn superseded(&self, key: &str, seq: u64) -> bool {
        let seen = self.seen.lock().unwrap_or_else(|e| e.into_inner());
        seen.get(key).is_some_and(|&s| s > seq)
    }
}

/// A counting semaphore: at most `n` computations at once.
pub struct Slots {
    free: Mutex<usize>,
    freed: Condvar,
}

/// A held slot, given back when dropped.
pub struct Slot<'a>(&'a Slots);

impl Slots {
    pub fn new(n: usize) -> Slots {
        Slots {
            free: Mutex::new(n.max(1)),
            freed: Condvar::new(),
        }
    }

    /// Waits for a slot while `keep_waiting()` holds (re-asked every
    /// 20 ms); `None` once it does not.
    pub fn take(&self, keep_waiting: impl Fn() -> bool) -> Option<Slot<'_>> {
        let mut free = self.free.lock().unwrap_or_else(|e| e.into_inner());
        loop {
            if !keep_waiting() {
                return None;
            }
            if *free > 0 {
                *free -= 1;
                return Some(Slot(self));
            }
            free = self
                .freed
                .wait_timeout(free, Duration::from_millis(20))
                .unwrap_or_else(|e| e.into_inner())
                .0;
        }
    }
}

impl Drop for Slot<'_> {
    fn drop(&mut self) {
        let mut free = self.0.free.lock().unwrap_or_else(|e| e.into_inner());
        *free += 1;
        self.0.freed.notify_one();
    }
}

/// What one request may spend.
#[derive(Clone, Copy, Debug)]
pub struct Budget {
    pub time: Duration,
    pub leaves: usize,
}

/// Why a computation stopped early.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Cut {
    /// A newer request of the same client and channel came.
    Superseded,
    /// The time budget ran out: the result is coarser, and says so.
    Budget,
}

/// One running request: its key and number, its start and budget.
pub struct Ticket<'a> {
    latest: &'a Latest,
    key: String,
    seq: u64,
    start: Instant,
    budget: Budget,
    cut: Mutex<Option<Cut>>,
}

impl<'a> Ticket<'a> {
    pub fn new(latest: &'a Latest, key: String, seq: u64, budget: Budget) -> Ticket<'a> {
        Ticket {
            latest,
            key,
            seq,
            start: Instant::now(),
            budget,
            cut: Mutex::new(None),
        }
    }

    pub fn superseded(&self) -> bool {
        self.latest.superseded(&self.key, self.seq)
    }

    /// The progress callback's answer: stop when superseded or out of time.
    pub fn flow(&self) -> ControlFlow<()> {
        let cut = if self.superseded() {
            Some(Cut::Superseded)
        } else if self.start.elapsed() > self.budget.time {
            Some(Cut::Budget)
        } else {
            None
        };
        match cut {
            Some(c) => {
                *self.cut.lock().unwrap_or_else(|e| e.into_inner()) = Some(c);
                ControlFlow::Break(())
            }
            None => ControlFlow::Continue(()),
        }
    }

    /// Why the computation was stopped, if it was.
    pub fn cut(&self) -> Option<Cut> {
        *self.cut.lock().unwrap_or_else(|e| e.into_inner())
    }

    pub fn budget(&self) -> Budget {
        self.budget
    }

    pub fn elapsed(&self) -> Duration {
        self.start.elapsed()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::sync::atomic::{AtomicUsize, Ordering};
    use std::sync::Arc;

    const LONG: Budget = Budget {
        time: Duration::from_secs(60),
        leaves: 1000,
    };

    #[test]
    fn a_newer_request_supersedes_an_older_one_of_its_key_only() {
        let latest = Latest::default();
        assert!(latest.arrive("a/atlas", 1));
        let t = Ticket::new(&latest, "a/atlas".into(), 1, LONG);
        assert_eq!(t.flow(), ControlFlow::Continue(()));
        assert!(latest.arrive("a/params", 7), "another channel");
        assert!(latest.arrive("b/atlas", 9), "another client");
        assert_eq!(t.flow(), ControlFlow::Continue(()));
        assert!(latest.arrive("a/atlas", 2));
        assert_eq!(t.flow(), ControlFlow::Break(()));
        assert_eq!(t.cut(), Some(Cut::Superseded));
        assert!(!latest.arrive("a/atlas", 1), "stale on arrival");
    }

    #[test]
    fn the_time_budget_cuts_and_says_so() {
        let latest = Latest::default();
        latest.arrive("k", 0);
        let b = Budget {
            time: Duration::ZERO,
            leaves: 1,
        };
        let t = Ticket::new(&latest, "k".into(), 0, b);
        std::thread::sleep(Duration::from_millis(2));
        assert_eq!(t.flow(), ControlFlow::Break(()));
        assert_eq!(t.cut(), Some(Cut::Budget));
    }

    #[test]
    fn no_more_than_n_run_at_once_and_waiters_can_give_up() {
        let slots = Arc::new(Slots::new(2));
        let running = Arc::new(AtomicUsize::new(0));
        let most = Arc::new(AtomicUsize::new(0));
        let handles: Vec<_> = (0..6)
            .map(|_| {
                let (slots, running, most) = (slots.clone(), running.clone(), most.clone());
                std::thread::spawn(move || {
                    let _slot = slots.take(|| true).unwrap();
                    let now = running.fetch_add(1, Ordering::SeqCst) + 1;
                    most.fetch_max(now, Ordering::SeqCst);
                    std::thread::sleep(Duration::from_millis(15));
                    running.fetch_sub(1, Ordering::SeqCst);
                })
            })
            .collect();
        for h in handles {
            h.join().unwrap();
        }
        assert_eq!(most.load(Ordering::SeqCst), 2);
        let _a = slots.take(|| true).unwrap();
        let _b = slots.take(|| true).unwrap();
        assert!(slots.take(|| false).is_none(), "a waiter that gives up");
    }
}
