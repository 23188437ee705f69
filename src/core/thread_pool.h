#pragma once
/// The process's worker threads for parallel element loops (issue 11, "threads that never
/// hurt"). Workers wait on a condition variable between loops: a waiting worker takes no CPU,
/// unlike an OpenMP team spinning after each region (libgomp's default), which on this
/// two-core machine made a 1215-DOF transient four times slower with two threads than with one
/// and, through OpenBLAS's OpenMP team, a 24k-DOF factorization 3.7 times slower.
///
/// A loop runs on the calling thread and up to max_threads() − 1 workers, started on first use.
/// Iterations are claimed in chunks of `grain` from a shared counter; results that must not
/// depend on the thread count are written per iteration (the caller sums them in order). The
/// caller never waits for a worker that has not started: when it has claimed the last chunk
/// the loop closes, so on a busy machine a loop costs at most a wake-up call more than a
/// serial one.
#include <functional>

namespace impactfe::threads {

/// Threads a loop may use (--threads; 0 restores the default: the machine's cores).
void set_max_threads(int n);
int max_threads();

/// Whether a core is free now for another thread of this process: fewer threads are runnable
/// on the machine, the caller included, than max_threads() (/proc/loadavg). False when that
/// cannot be read. A helper thread that takes work off the caller's (the results writer's)
/// pays for the handing over in CPU time: on a busy machine it would only add that.
bool core_idle();

/// body(i) for every i in [0, n), on up to max_threads() threads. When iterations throw, the
/// exception of the lowest such i is rethrown after the loop (the one a serial loop would
/// throw), whatever the thread count. A loop started inside another runs serially.
void parallel_for(int n, int grain, const std::function<void(int)>& body);

}  // namespace impactfe::threads
