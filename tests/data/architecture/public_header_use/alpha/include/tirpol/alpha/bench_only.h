#pragma once
namespace alpha {
struct BenchOnly {};
}  // namespace alpha
