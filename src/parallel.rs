//! Fanning independent jobs out over threads while handing their results back in job order, so
//! that everything a command writes or prints is bit-identical whatever the number of threads.
//!
//! The jobs run on `std::thread::scope` threads pulling the next job index from a shared
//! counter; the caller's thread receives the results, reorders them, and consumes each in index
//! order as soon as it and every job before it are done. At most a window of
//! [`WINDOW_PER_THREAD`] results per thread may wait ahead of the consumer, so what is held in
//! memory is bounded by the threads, not by the number of jobs.

use std::collections::BTreeMap;
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::sync::{mpsc, Condvar, Mutex};

/// How many results per thread may be finished ahead of the one the consumer waits for.
pub const WINDOW_PER_THREAD: usize = 4;

/// The default number of threads: the cores this process may use (1 if unknown).
pub fn default_jobs() -> usize {
    std::thread::available_parallelism().map_or(1, |n| n.get())
}

/// Runs `work(state, i)` for every `i` in `0..n` on `jobs` threads and calls `consume(i, result)`
/// for each, in increasing `i`, on the caller's thread. Each thread makes its own `state` with
/// `init` (a cache of what its jobs share, such as a level's built geometry). With `jobs <= 1`
/// everything runs on the caller's thread, in order, with no thread started.
///
/// The first error `consume` returns stops the fan-out (jobs already started finish, no new one
/// starts) and is returned.
pub fn for_each_ordered<S, R, E>(
    jobs: usize,
    n: usize,
    init: impl Fn() -> S + Sync,
    work: impl Fn(&mut S, usize) -> R + Sync,
    mut consume: impl FnMut(usize, R) -> Result<(), E>,
) -> Result<(), E>
where
    R: Send,
{
    let jobs = jobs.clamp(1, n.max(1));
    if jobs == 1 {
        let mut state = init();
        for i in 0..n {
            consume(i, work(&mut state, i))?;
        }
        return Ok(());
    }
    let window = WINDOW_PER_THREAD * jobs;
    let next = AtomicUsize::new(0);
    let stop = AtomicBool::new(false);
    // The number of results consumed so far, which a thread waits on to stay within the window.
    let consumed = (Mutex::new(0usize), Condvar::new());
    let (tx, rx) = mpsc::channel::<(usize, R)>();
    std::thread::scope(|scope| {
        for _ in 0..jobs {
            let tx = tx.clone();
            let (next, stop, consumed, init, work) = (&next, &stop, &consumed, &init, &work);
            scope.spawn(move || {
                let mut state = init();
                loop {
                    let i = next.fetch_add(1, Ordering::SeqCst);
                    if i >= n || stop.load(Ordering::SeqCst) {
                        break;
                    }
                    {
                        let (lock, cv) = consumed;
                        let mut done = lock.lock().unwrap_or_else(|p| p.into_inner());
                        while i >= *done + window && !stop.load(Ordering::SeqCst) {
                            done = cv.wait(done).unwrap_or_else(|p| p.into_inner());
                        }
                    }
                    if stop.load(Ordering::SeqCst) {
                        break;
                    }
                    if tx.send((i, work(&mut state, i))).is_err() {
                        break;
                    }
                }
            });
        }
        drop(tx);
        let mut pending: BTreeMap<usize, R> = BTreeMap::new();
        let mut want = 0usize;
        let mut result = Ok(());
        'receive: for (i, r) in rx.iter() {
            pending.insert(i, r);
            while let Some(r) = pending.remove(&want) {
                result = consume(want, r);
                want += 1;
                let (lock, cv) = &consumed;
                *lock.lock().unwrap_or_else(|p| p.into_inner()) = want;
                cv.notify_all();
                if result.is_err() {
                    break 'receive;
                }
            }
        }
        // Stop the threads (on an error; after the last job this changes nothing) and wake those
        // waiting on the window; dropping the receiver makes a finished job's send fail.
        stop.store(true, Ordering::SeqCst);
        consumed.1.notify_all();
        drop(rx);
        result
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn results_arrive_in_order_whatever_the_threads() {
        for jobs in [1, 2, 3, 8] {
            let mut seen = Vec::new();
            // Later jobs finish sooner (they sleep less), so an unordered hand-back would show.
            for_each_ordered(
                jobs,
                40,
                || 0u32,
                |calls, i| {
                    *calls += 1;
                    std::thread::sleep(std::time::Duration::from_micros(((40 - i) * 50) as u64));
                    i * i
                },
                |i, r| {
                    seen.push((i, r));
                    Ok::<(), ()>(())
                },
            )
            .unwrap();
            let want: Vec<(usize, usize)> = (0..40).map(|i| (i, i * i)).collect();
            assert_eq!(seen, want, "jobs = {jobs}");
        }
    }

    #[test]
    fn an_error_of_the_consumer_stops_the_fan_out_and_is_returned() {
        let started = AtomicUsize::new(0);
        let mut consumed = 0;
        let r = for_each_ordered(
            2,
            10_000,
            || (),
            |_, i| {
                started.fetch_add(1, Ordering::SeqCst);
                i
            },
            |i, _| {
                consumed += 1;
                if i == 5 {
                    Err(i)
                } else {
                    Ok(())
                }
            },
        );
        assert_eq!(r, Err(5));
        assert_eq!(consumed, 6);
        // A job starts only while its index is under consumed + window (2 threads x
        // WINDOW_PER_THREAD), and at most 6 were consumed: jobs 0..14 at most ever started.
        let ran = started.load(Ordering::SeqCst);
        assert!(
            ran <= 6 + 2 * WINDOW_PER_THREAD,
            "{ran} jobs ran for 6 consumed"
        );
    }

    #[test]
    fn no_jobs_consume_nothing() {
        let r = for_each_ordered(
            4,
            0,
            || (),
            |_, i| i,
            |_, _| -> Result<(), ()> { panic!("nothing to consume") },
        );
        assert_eq!(r, Ok(()));
    }
}
