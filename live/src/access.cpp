#include "access.h"

#include <arpa/inet.h>
#include <ifaddrs.h>
#include <net/if.h>
#include <netinet/in.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <random>

namespace tirpol::live {

bool is_loopback_address(const std::string& address) {
    return address == "localhost" || address == "::1" || address.rfind("127.", 0) == 0;
}

std::vector<std::string> interface_addresses() {
    std::vector<std::string> addresses;
    ifaddrs* list = nullptr;
    if (::getifaddrs(&list) != 0) return addresses;
    for (const ifaddrs* a = list; a != nullptr; a = a->ifa_next) {
        if (a->ifa_addr == nullptr || (a->ifa_flags & IFF_UP) == 0) continue;
        std::array<char, INET6_ADDRSTRLEN> text{};
        const int family = a->ifa_addr->sa_family;
        const void* raw = nullptr;
        if (family == AF_INET) raw = &reinterpret_cast<const sockaddr_in*>(a->ifa_addr)->sin_addr;
        if (family == AF_INET6)
            raw = &reinterpret_cast<const sockaddr_in6*>(a->ifa_addr)->sin6_addr;
        if (raw != nullptr && ::inet_ntop(family, raw, text.data(), text.size()) != nullptr)
            addresses.emplace_back(text.data());
    }
    ::freeifaddrs(list);
    return addresses;
}

std::string host_name() {
    std::array<char, 256> name{};
    if (::gethostname(name.data(), name.size() - 1) != 0) return "";
    return name.data();
}

std::string reachable_address(const std::string& bind_address) {
    return reachable_addresses(bind_address).front();
}

std::vector<std::string> reachable_addresses(const std::string& bind_address) {
    if (bind_address != "0.0.0.0" && bind_address != "::" && !bind_address.empty())
        return {bind_address};
    std::vector<std::string> ipv4, ipv6;
    for (const std::string& a : interface_addresses()) {
        if (is_loopback_address(a)) continue;
        if (a.find(':') == std::string::npos) {
            if (std::find(ipv4.begin(), ipv4.end(), a) == ipv4.end()) ipv4.push_back(a);
        } else if (a.rfind("fe80", 0) != 0 &&  // link-local needs a zone index no URL can carry
                   std::find(ipv6.begin(), ipv6.end(), a) == ipv6.end()) {
            ipv6.push_back(a);
        }
    }
    ipv4.insert(ipv4.end(), ipv6.begin(), ipv6.end());
    if (ipv4.empty()) ipv4.push_back("127.0.0.1");
    return ipv4;
}

std::string make_access_token() {
    std::random_device device;
    std::uniform_int_distribution<int> digit(0, 15);
    std::string token;
    for (int i = 0; i < 32; ++i) token.push_back("0123456789abcdef"[digit(device)]);
    return token;
}

bool token_matches(const std::string& presented, const std::string& token) {
    if (presented.size() != token.size() || token.empty()) return false;
    unsigned char diff = 0;
    for (std::size_t i = 0; i < token.size(); ++i)
        diff |= static_cast<unsigned char>(presented[i] ^ token[i]);
    return diff == 0;
}

}  // namespace tirpol::live
