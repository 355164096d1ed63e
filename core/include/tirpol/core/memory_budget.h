#pragma once
/// \file memory_budget.h
/// Checking a job's memory estimate against what the machine has, before allocating: a render or
/// a table that cannot fit is refused with its estimate instead of ending in std::bad_alloc, the
/// OOM killer or swap.

#include <cstdint>
#include <optional>
#include <string_view>

namespace tirpol {

/// MemAvailable from /proc/meminfo, bytes (the kernel's estimate of what can be allocated without
/// swapping); nullopt where it cannot be read (not Linux).
std::optional<std::uint64_t> available_memory_bytes();

/// Throws tirpol::Error "<what>: needs an estimated N GiB of memory, more than the M GiB available
/// (limits::kMaxMemoryFraction of MemAvailable)" when `estimate_bytes` exceeds that budget.
/// `available_bytes` stands in for available_memory_bytes() (tests); without either, no check.
void check_memory_estimate(std::uint64_t estimate_bytes, std::string_view what,
                           std::optional<std::uint64_t> available_bytes = available_memory_bytes());

}  // namespace tirpol
