#include "tirpol/live/access.h"

#include <random>

namespace tirpol::live {

bool is_loopback_address(const std::string& address) {
    return address == "localhost" || address == "::1" || address.rfind("127.", 0) == 0;
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
    for (std::size_t i = 0; i < token.size(); ++i) diff |= static_cast<unsigned char>(presented[i] ^ token[i]);
    return diff == 0;
}

}  // namespace tirpol::live
