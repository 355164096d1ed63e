#pragma once
namespace alpha {
struct OwnOnly {};
}  // namespace alpha
