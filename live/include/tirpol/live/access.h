#pragma once
/// \file access.h
/// Who may use the live view. On the loopback interface (the default) anyone on the laptop may, as
/// with any local tool. Bound to another address the page can be reached from the network, so every
/// request must carry a random token printed at start: `?token=…` in the URL (the page passes it on
/// to each of its own requests; a request with it also sets an HttpOnly cookie that covers the page's
/// script and style sheet), the header `X-Tirpol-Token`, or that cookie.

#include <string>

namespace tirpol::live {

/// True for 127.0.0.0/8, ::1 and "localhost".
bool is_loopback_address(const std::string& address);

/// 128 random bits from std::random_device as 32 hexadecimal digits.
std::string make_access_token();

/// Whether `presented` equals `token`, compared in time independent of where they differ.
bool token_matches(const std::string& presented, const std::string& token);

}  // namespace tirpol::live
