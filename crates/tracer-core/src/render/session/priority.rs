//! Render workers run at a lower CPU priority than the interactive thread.

/// How much render workers lower their priority (Linux nice increment), unless the
/// environment variable `RAYGINE_WORKER_NICE` (0..=19) says otherwise.
pub const DEFAULT_WORKER_NICE: i32 = 10;

/// Render workers yield the CPU to the interactive thread (the viewer's UI, the desktop's
/// software OpenGL): on Linux each thread has its own nice value.
pub(super) fn lower_thread_priority() {
    #[cfg(target_os = "linux")]
    {
        let increment = std::env::var("RAYGINE_WORKER_NICE")
            .ok()
            .and_then(|v| v.trim().parse::<i32>().ok())
            .map_or(DEFAULT_WORKER_NICE, |n| n.clamp(0, 19));
        if increment > 0 {
            // SAFETY: `nice` takes a plain integer and only changes the calling thread's
            // scheduling priority; it touches no memory of ours. A failure (-1 with errno) leaves
            // the priority as it was, which is harmless, so the result is deliberately ignored.
            unsafe {
                libc::nice(increment);
            }
        }
    }
}
