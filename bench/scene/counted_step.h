#pragma once
// Marks the timed step call for callgrind, so that `bench/compare.sh --instructions` counts the
// instructions of the steps alone (valgrind --collect-atstart=no): a count that the machine's
// load does not move, unlike the wall clock. Outside valgrind the marks cost a few instructions;
// without valgrind's header they are nothing.

#if __has_include(<valgrind/callgrind.h>)
#include <valgrind/callgrind.h>
#define BENCHSCENE_TOGGLE_COUNTING() CALLGRIND_TOGGLE_COLLECT
#else
#define BENCHSCENE_TOGGLE_COUNTING() ((void)0)
#endif

namespace benchscene {

// Counting is on for the lifetime of one of these.
class CountedStep {
public:
    CountedStep() { BENCHSCENE_TOGGLE_COUNTING(); }
    ~CountedStep() { BENCHSCENE_TOGGLE_COUNTING(); }
    CountedStep(const CountedStep&) = delete;
    CountedStep& operator=(const CountedStep&) = delete;
};

}  // namespace benchscene
