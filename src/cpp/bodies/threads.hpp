// Threads of the element loop (docs/guide/performance.md, "Both cores"): a body's element
// forces and tangents computed by several threads, each its own range of elements, and added
// into the assembled vector and band in element order by the calling thread, so that the sums
// are those of one thread bit for bit, whatever the number of threads.
//
// One pool for the process, of assembly_threads() - 1 workers started at the first parallel
// loop.  A loop that finds the pool in use by another thread (a second run, an output worker)
// runs on its calling thread alone; a worker that has not woken when the caller is done with
// its own range leaves its range to the caller.  Either way the result is the same.
#pragma once

namespace rancf {

/// Threads an element loop may use (1: the calling thread alone, the default).
void set_assembly_threads(int n);
int assembly_threads();

/// The fewest elements a body has for its loop to be shared: below, a wake-up costs more than
/// the elements it shares.
inline constexpr int kMinParallelElements = 64;

/// Run job(ctx, c) for every chunk c = 0 .. n_chunks - 1, chunk 0 on the calling thread,
/// the others on the pool's workers or, where none took them, the calling thread; returns
/// when every chunk is done.  False (nothing run) if the pool is in use by another thread or
/// by this one (a loop inside a chunk) or has no workers: the caller then runs the loop alone.
bool run_chunks(int n_chunks, void (*job)(void* ctx, int chunk), void* ctx);

}  // namespace rancf
