#pragma once
/// \file access.h
/// Who may use the live view. On the loopback interface (the default) anyone on the laptop may, as
/// with any local tool. Bound to another address the page can be reached from the network, so every
/// request must carry a random token printed at start: `?token=…` in the URL (the page passes it on
/// to each of its own requests; a request with it also sets an HttpOnly cookie that covers the
/// page's script and style sheet), the header `X-Tirpol-Token`, or that cookie.

#include <string>
#include <vector>

namespace tirpol::live {

/// True for 127.0.0.0/8, ::1 and "localhost".
bool is_loopback_address(const std::string& address);

/// The IPv4 and IPv6 addresses of this machine's interfaces that are up (loopback included), as
/// text ("192.168.1.20", "fe80::1"); empty if they cannot be listed.
std::vector<std::string> interface_addresses();

/// This machine's host name (gethostname), or "" if it has none.
std::string host_name();

/// The address another machine would use to reach a server bound to `bind_address`: that address
/// itself, or for a wildcard bind (0.0.0.0, ::) the first non-loopback IPv4 address of an interface
/// (else the first non-loopback IPv6 one, else 127.0.0.1).
std::string reachable_address(const std::string& bind_address);

/// Every address another machine could use: for a wildcard bind each non-loopback IPv4 address of
/// an interface, then each non-loopback, non-link-local IPv6 one (a laptop on Ethernet and Wi-Fi
/// has several; the operator picks the one of the tablet's network); else reachable_address alone.
/// Never empty; the first is reachable_address(bind_address).
std::vector<std::string> reachable_addresses(const std::string& bind_address);

/// 128 random bits from std::random_device as 32 hexadecimal digits.
std::string make_access_token();

/// Whether `presented` equals `token`, compared in time independent of where they differ.
bool token_matches(const std::string& presented, const std::string& token);

}  // namespace tirpol::live
