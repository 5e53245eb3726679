//! One background job at a time, keyed by what it depends on: a new key cancels the running job
//! (cooperatively, through its flag) and clears its results; the UI thread polls the latest
//! results and never waits. The measure and glare workers are built on it.

use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Mutex};

/// What a started job holds: its cancel flag and the slot it publishes results into.
#[derive(Debug)]
pub struct JobHandles<R> {
    pub cancel: Arc<AtomicBool>,
    pub latest: Arc<Mutex<Option<R>>>,
}

impl<R> JobHandles<R> {
    /// Whether the job was replaced or dropped.
    pub fn cancelled(&self) -> bool {
        self.cancel.load(Ordering::Acquire)
    }

    /// Makes `r` the latest result.
    pub fn publish(&self, r: R) {
        if let Ok(mut l) = self.latest.lock() {
            *l = Some(r);
        }
    }
}

/// The current job's key, cancel flag and latest result.
#[derive(Debug)]
pub struct Restartable<K, R> {
    key: Option<K>,
    cancel: Option<Arc<AtomicBool>>,
    latest: Arc<Mutex<Option<R>>>,
}

impl<K, R> Default for Restartable<K, R> {
    fn default() -> Self {
        Restartable {
            key: None,
            cancel: None,
            latest: Arc::new(Mutex::new(None)),
        }
    }
}

impl<K: PartialEq, R: Clone> Restartable<K, R> {
    /// None while `key` is the current one; else cancels the current job, forgets its results
    /// and returns the handles of a new job for `key` (which the caller may leave unstarted).
    pub fn restart(&mut self, key: K) -> Option<JobHandles<R>> {
        if self.key.as_ref() == Some(&key) {
            return None;
        }
        if let Some(c) = self.cancel.take() {
            c.store(true, Ordering::Release);
        }
        self.latest = Arc::new(Mutex::new(None));
        self.key = Some(key);
        let cancel = Arc::new(AtomicBool::new(false));
        self.cancel = Some(Arc::clone(&cancel));
        Some(JobHandles {
            cancel,
            latest: Arc::clone(&self.latest),
        })
    }

    /// The current job's latest result (None before its first).
    pub fn latest(&self) -> Option<R> {
        self.latest.lock().ok().and_then(|l| l.clone())
    }
}

impl<K, R> Drop for Restartable<K, R> {
    fn drop(&mut self) {
        if let Some(c) = self.cancel.take() {
            c.store(true, Ordering::Release);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_new_key_cancels_the_job_and_forgets_its_results() {
        let mut r: Restartable<u32, &str> = Restartable::default();
        let first = r.restart(1).unwrap_or_else(|| unreachable!());
        first.publish("one");
        assert_eq!(r.latest(), Some("one"));
        assert!(r.restart(1).is_none(), "the same key keeps the job");
        let second = r.restart(2).unwrap_or_else(|| unreachable!());
        assert!(first.cancelled() && !second.cancelled());
        assert_eq!(r.latest(), None);
        first.publish("stale");
        assert_eq!(r.latest(), None, "a replaced job publishes nowhere visible");
        drop(r);
        assert!(second.cancelled());
    }
}
