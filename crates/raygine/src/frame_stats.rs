//! The UI's frame times while rendering: the interval between frames and the time the app itself
//! spent in each (the rest is egui's tessellation, OpenGL and waiting for the next frame), for
//! the p95 in the status bar and the `RAYGINE_FRAME_STATS` log.

use std::collections::VecDeque;
use std::time::{Duration, Instant};

/// Frames kept in each window.
const WINDOW: usize = 600;

#[derive(Debug)]
pub struct FrameStats {
    /// Recent UI frame intervals while rendering, seconds.
    intervals: VecDeque<f32>,
    /// Time the app itself spent in recent frames while rendering, seconds.
    work: VecDeque<f32>,
    last_frame: Option<Instant>,
    /// When the log line was last printed (None: no log).
    log: Option<Instant>,
    started: Instant,
}

impl FrameStats {
    /// Empty windows; `log`: print a line every 2 s (`RAYGINE_FRAME_STATS`).
    pub fn new(log: bool) -> Self {
        Self {
            intervals: VecDeque::new(),
            work: VecDeque::new(),
            last_frame: None,
            log: log.then(Instant::now),
            started: Instant::now(),
        }
    }

    /// Whether the log is on.
    pub fn logging(&self) -> bool {
        self.log.is_some()
    }

    /// Time since these statistics were made (with the app).
    pub fn since_start(&self) -> Duration {
        self.started.elapsed()
    }

    /// At the start of a frame: the interval since the last one counts while `rendering`.
    /// True when the log line is due.
    pub fn frame_started(&mut self, rendering: bool) -> bool {
        let now = Instant::now();
        if let Some(last) = self.last_frame.replace(now)
            && rendering
        {
            push(&mut self.intervals, now.duration_since(last).as_secs_f32());
        }
        match self.log {
            Some(t) if t.elapsed() > Duration::from_secs(2) => {
                self.log = Some(now);
                true
            }
            _ => false,
        }
    }

    /// At the end of a frame: the app's own time in it, counted while `rendering`.
    pub fn frame_done(&mut self, rendering: bool, work_secs: f32) {
        if rendering {
            push(&mut self.work, work_secs);
        }
    }

    /// The 95th percentile of recent frame intervals while rendering, milliseconds.
    pub fn p95_ms(&self) -> Option<f32> {
        p95_ms(&self.intervals)
    }

    /// The 95th percentile of the app's own time in recent frames, milliseconds.
    pub fn p95_work_ms(&self) -> Option<f32> {
        p95_ms(&self.work)
    }

    /// Frame intervals in the window.
    pub fn frames(&self) -> usize {
        self.intervals.len()
    }
}

fn push(window: &mut VecDeque<f32>, secs: f32) {
    window.push_back(secs);
    if window.len() > WINDOW {
        window.pop_front();
    }
}

/// The 95th percentile of a window of durations (seconds), in milliseconds.
fn p95_ms(window: &VecDeque<f32>) -> Option<f32> {
    if window.len() < 10 {
        return None;
    }
    let mut v: Vec<f32> = window.iter().copied().collect();
    v.sort_by(f32::total_cmp);
    let i = ((v.len() as f32 * 0.95) as usize).min(v.len() - 1);
    Some(v[i] * 1e3)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_p95_needs_ten_frames_and_ignores_idle_ones() {
        let mut stats = FrameStats::new(false);
        for _ in 0..9 {
            stats.frame_done(true, 0.010);
        }
        stats.frame_done(false, 1.0);
        assert_eq!(stats.p95_work_ms(), None);
        stats.frame_done(true, 0.020);
        assert_eq!(stats.p95_work_ms(), Some(20.0));
    }
}
