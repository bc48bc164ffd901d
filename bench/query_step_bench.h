// SPDX-License-Identifier: MIT
#pragma once
// rewind_query_bench's step families (query_step_bench.cpp).

namespace rwd::bench::query_level {

/// Registers Step/level/* and Step/ground/* for every engine built in: 200
/// bodies dropped over the 10,000-box level, or over the ground alone.
void register_step_benchmarks();

}  // namespace rwd::bench::query_level
