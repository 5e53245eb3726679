//! A trial read in a child process. openusd 0.6 allocates what the counts in a `.usdc` (or a
//! `.usdz` holding one) declare before checking them against the file; a count beyond memory
//! makes the allocation fail, and Rust aborts the process on a failed allocation (it cannot be
//! caught as a panic can). So the stage is first read in a forked child: if the child dies,
//! the file is refused with an error and the parse that would have taken the viewer down never
//! runs in it. A child that reads the file to the end exits 0 (or 1 on a clean error, which
//! the real read then reports).
//!
//! openusd 0.6 also loops without end on some malformed files (the fuzzer found one: its
//! instancing resolution recursing); a child that has not finished after [`limit`] is killed
//! and the file refused.
//!
//! The child shares the parent's memory copy-on-write and runs only the read (no other
//! thread exists in it); glibc's allocator resets its locks across fork. Unix only; elsewhere
//! the read runs unguarded.

/// How long the trial may take: `given` seconds, else `RAYGINE_USD_TRIAL_SECS`, else 60 s and
/// 2 s a megabyte of the file opened (its layers are not counted).
pub(super) fn limit(given: Option<f64>, file_bytes: u64) -> std::time::Duration {
    let secs = given
        .or_else(|| {
            std::env::var("RAYGINE_USD_TRIAL_SECS")
                .ok()
                .and_then(|s| s.trim().parse::<f64>().ok())
        })
        .filter(|s| s.is_finite() && *s > 0.0)
        .unwrap_or(60.0 + 2.0 * file_bytes as f64 / 1e6);
    std::time::Duration::from_secs_f64(secs)
}

/// Reads the file in a child with `read`, for at most `limit`; `Err` says how the child died.
#[cfg(unix)]
pub(super) fn trial_read(
    limit: std::time::Duration,
    read: impl FnOnce() -> bool,
) -> Result<(), String> {
    // SAFETY: fork has no preconditions; the child only runs `read` and leaves by `_exit`,
    // never returning into the parent's code or running its destructors.
    let pid = unsafe { libc::fork() };
    if pid < 0 {
        // No child to try it in: read it here, as without the guard.
        return Ok(());
    }
    if pid == 0 {
        // The child's own failure report (the allocator's message, a backtrace) would only
        // repeat what the parent says: send it nowhere.
        // SAFETY: plain descriptor calls on a path literal and the child's own fd 2.
        unsafe {
            let null = libc::open(c"/dev/null".as_ptr(), libc::O_WRONLY);
            if null >= 0 {
                libc::dup2(null, 2);
            }
        }
        let ok = std::panic::catch_unwind(std::panic::AssertUnwindSafe(read)).unwrap_or(false);
        // SAFETY: ends the child at once, as a forked child must.
        unsafe { libc::_exit(if ok { 0 } else { 1 }) };
    }
    let mut status = 0;
    let started = std::time::Instant::now();
    loop {
        // SAFETY: polls the child just forked; `status` is a valid out-pointer.
        let r = unsafe { libc::waitpid(pid, &mut status, libc::WNOHANG) };
        if r == pid {
            break;
        }
        if r < 0 && std::io::Error::last_os_error().kind() != std::io::ErrorKind::Interrupted {
            return Ok(());
        }
        if started.elapsed() > limit {
            // SAFETY: ends and reaps our own child.
            unsafe {
                libc::kill(pid, libc::SIGKILL);
                libc::waitpid(pid, &mut status, 0);
            }
            return Err(format!(
                "the USD reader (openusd 0.6) did not finish reading this file within {:.0} s \
                 (it loops on some damaged files; RAYGINE_USD_TRIAL_SECS sets the limit)",
                limit.as_secs_f64()
            ));
        }
        std::thread::sleep(std::time::Duration::from_millis(2));
    }
    if libc::WIFSIGNALED(status) {
        let signal = libc::WTERMSIG(status);
        let why = match signal {
            libc::SIGABRT => "it aborted (a size the file declares cannot be allocated)".to_owned(),
            libc::SIGKILL => "it was killed (out of memory?)".to_owned(),
            libc::SIGSEGV => "it crashed (segmentation fault)".to_owned(),
            other => format!("it died of signal {other}"),
        };
        return Err(format!(
            "the USD reader (openusd 0.6) cannot read this file: a trial read in a child \
             process failed, {why}; the file is damaged or declares more than it holds"
        ));
    }
    Ok(())
}

#[cfg(not(unix))]
pub(super) fn trial_read(
    _limit: std::time::Duration,
    _read: impl FnOnce() -> bool,
) -> Result<(), String> {
    Ok(())
}
