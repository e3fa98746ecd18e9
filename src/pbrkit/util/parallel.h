#pragma once
// pbrkit::parallel_for: oneTBB's parallel_for, made visible to ThreadSanitizer.
//
// Every parallel loop in pbrkit goes through these overloads instead of calling
// tbb::parallel_for directly. Call them qualified, `pbrkit::parallel_for(...)`: with a
// oneTBB range argument an unqualified call also finds tbb::parallel_for by argument-
// dependent lookup, and C++20 overload resolution prefers its constrained template. In an ordinary
// build each one is a plain forwarding call to the same tbb::parallel_for form (the same range,
// body and default auto_partitioner), so the generated code, the schedule and every result are
// unchanged.
//
// Why: the oneTBB library pbrkit links (Debian's libtbb.so) is not built with
// ThreadSanitizer. The happens-before edges that parallel_for guarantees are created inside
// that library (spawning a task publishes the caller's writes to the worker that runs it;
// waiting for the loop's completion publishes every body's writes back to the caller), so
// TSan cannot see them and reports the caller's writes before or after a loop as racing
// with a worker's accesses inside it. Under ThreadSanitizer (`__SANITIZE_THREAD__` with
// GCC, `__has_feature(thread_sanitizer)` with Clang) the overloads below state exactly
// those two edges with the TSan annotation interface, and no others:
//   - the caller releases `start` before the loop and every body invocation acquires it
//     before running: what the caller wrote before the loop happens before every body;
//   - every body invocation releases `end` when it finishes (also when it throws) and the
//     caller acquires it after the loop: every body happens before what follows the loop.
// Bodies never acquire `end`, so no edge is added between two body invocations: a body
// that writes what another one reads or writes without synchronisation of its own is
// still reported, whichever threads ran them and in whatever order.
// tests/tsan.supp covers the remaining false reports, which come from oneTBB's own
// header-inlined task bookkeeping racing with itself.
//
// A loop inside tbb::task_arena::execute needs nothing more: execute runs its functor on
// the calling thread whenever that thread can join the arena, which it always can for an
// arena that only one thread uses (one slot is reserved for it), so no edge is missing
// there. Only an execute that oneTBB hands to another thread (an arena shared by several
// external threads, all its reserved slots taken) would need the same pair of edges.

#include <tbb/blocked_range.h>
#include <tbb/blocked_range2d.h>
#include <tbb/parallel_for.h>

#if defined(__SANITIZE_THREAD__)
#define PBRKIT_TSAN_ANNOTATIONS 1
#elif defined(__has_feature)
#if __has_feature(thread_sanitizer)
#define PBRKIT_TSAN_ANNOTATIONS 1
#endif
#endif

#if defined(PBRKIT_TSAN_ANNOTATIONS)
#include <sanitizer/tsan_interface.h>
#endif

namespace pbrkit {

#if defined(PBRKIT_TSAN_ANNOTATIONS)
// Part of the TSan runtime's dynamic-annotation interface (not declared by
// <sanitizer/tsan_interface.h>): the calling thread's reads are not checked in between.
extern "C" void AnnotateIgnoreReadsBegin(const char* file, int line);
extern "C" void AnnotateIgnoreReadsEnd(const char* file, int line);

namespace parallel_detail {

// The two synchronisation addresses of one loop: TSan keys its sync objects by address,
// and two distinct bytes keep the "before the loop" and "after the loop" edges apart.
struct LoopEdges {
  char start = 0;
  char end = 0;
};

// Releases `start` on construction and acquires `end` on destruction: the calling thread,
// around the loop (also when a body's exception propagates out of it).
class CallerEdges {
 public:
  explicit CallerEdges(LoopEdges& edges) : edges_(edges) { __tsan_release(&edges_.start); }
  ~CallerEdges() { __tsan_acquire(&edges_.end); }
  CallerEdges(const CallerEdges&) = delete;
  CallerEdges& operator=(const CallerEdges&) = delete;

 private:
  LoopEdges& edges_;
};

// The body handed to tbb::parallel_for. oneTBB copies it into its task objects and passes
// each invocation a subrange that lives in a task object (or in the running thread's
// partitioner state): memory that oneTBB's task code wrote, on whichever thread split or
// spawned the task, and that reaches this thread through the uninstrumented library. Those
// two things (the pointers below and the subrange's bounds) are copied with read checks
// off; only then does the invocation acquire `start`, and everything of the caller's
// (`body` and what it touches) is read after that. On return, also by an exception, it
// releases `end`.
template <typename Range, typename Body>
class BodyWithEdges {
 public:
  BodyWithEdges(LoopEdges& edges, const Body& body) : edges_(&edges), body_(&body) {}

  void operator()(const Range& r) const {
    AnnotateIgnoreReadsBegin(__FILE__, __LINE__);
    const Range piece = r;
    LoopEdges* const edges = edges_;
    const Body* const body = body_;
    AnnotateIgnoreReadsEnd(__FILE__, __LINE__);
    __tsan_acquire(&edges->start);
    struct Release {
      LoopEdges* edges;
      ~Release() { __tsan_release(&edges->end); }
    } release{edges};
    (*body)(piece);
  }

 private:
  LoopEdges* edges_;
  const Body* body_;
};

}  // namespace parallel_detail
#endif

/// tbb::parallel_for(range, body): calls body(subrange) on pieces of a tbb::blocked_range,
/// blocked_range2d (or any other oneTBB range), in parallel (see the top of this file).
template <typename Range, typename Body>
void parallel_for(const Range& range, const Body& body) {
#if defined(PBRKIT_TSAN_ANNOTATIONS)
  parallel_detail::LoopEdges edges;
  const parallel_detail::BodyWithEdges<Range, Body> with_edges(edges, body);
  const parallel_detail::CallerEdges caller(edges);
  tbb::parallel_for(range, with_edges);
#else
  tbb::parallel_for(range, body);
#endif
}

/// tbb::parallel_for(first, last, f): calls f(i) for every i in [first, last), in
/// parallel (see the comment at the top of this file).
template <typename Index, typename Function>
void parallel_for(Index first, Index last, const Function& f) {
#if defined(PBRKIT_TSAN_ANNOTATIONS)
  // oneTBB's own index form wraps f in a parallel_for_body_wrapper that refers to f (on
  // the caller's stack) and calls it with no chance for an acquire in between, so under
  // TSan the loop is the range form above instead: the same blocked_range<Index>, over
  // [first, last) rather than oneTBB's [0, last - first) plus first, and the same auto
  // partitioner; only the schedule may differ, never a result.
  if (!(first < last)) return;
  pbrkit::parallel_for(tbb::blocked_range<Index>(first, last),
                       [&f](const tbb::blocked_range<Index>& r) {
                         for (Index i = r.begin(); i != r.end(); ++i) f(i);
                       });
#else
  tbb::parallel_for(first, last, f);
#endif
}

}  // namespace pbrkit
