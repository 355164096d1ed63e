#pragma once
namespace alpha {
struct Member {};
}  // namespace alpha
