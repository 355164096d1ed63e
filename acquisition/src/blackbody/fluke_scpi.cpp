#include "tirpol/acquisition/internal/fluke_scpi.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <cmath>

namespace tirpol::acquisition::fluke_scpi {

namespace {

std::string upper(std::string_view s) {
    std::string out(s);
    for (char& c : out) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
    return out;
}

std::string_view trim(std::string_view s) {
    while (!s.empty() && std::isspace(static_cast<unsigned char>(s.front()))) s.remove_prefix(1);
    while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back()))) s.remove_suffix(1);
    return s;
}

/// SCPI keywords of the commands we use: long form, short form (the upper-case part in the manual).
struct Keyword {
    std::string_view long_form, short_form;
};
constexpr std::array kKeywords{
    Keyword{"SOURCE", "SOUR"},     Keyword{"SPOINT", "SPO"},      Keyword{"SENSE", "SENS"},
    Keyword{"DATA", "DATA"},       Keyword{"STABILITY", "STAB"},  Keyword{"TEST", "TEST"},
    Keyword{"LIMIT", "LIM"},       Keyword{"PROTECTION", "PROT"}, Keyword{"TRIPPED", "TRIP"},
    Keyword{"SYSTEM", "SYST"},     Keyword{"ERROR", "ERR"},       Keyword{"UNIT", "UNIT"},
    Keyword{"TEMPERATURE", "TEMP"}};

}  // namespace

std::string set_point_command(double set_point_c) {
    return fmt::format("SOUR:SPO {:.3f}\n", set_point_c);
}
std::string stability_limit_command(double limit_c) {
    return fmt::format("SOUR:STAB:LIM {:.3f}\n", limit_c);
}

std::string canonical_header(std::string_view header) {
    std::string text = upper(trim(header));
    const bool query = !text.empty() && text.back() == '?';
    if (query) text.pop_back();
    std::string out;
    std::size_t start = 0;
    while (start <= text.size()) {
        const auto colon = text.find(':', start);
        const std::string word =
            text.substr(start, colon == std::string::npos ? std::string::npos : colon - start);
        std::string canonical = word;
        for (const auto& k : kKeywords)
            if (word == k.long_form || word == k.short_form) canonical = k.short_form;
        out += (start == 0 ? "" : ":") + canonical;
        if (colon == std::string::npos) break;
        start = colon + 1;
    }
    return query ? out + "?" : out;
}

std::optional<double> parse_number(std::string_view reply) {
    reply = trim(reply);
    if (!reply.empty() && reply.front() == '+') reply.remove_prefix(1);
    double v = 0.0;
    const auto r = std::from_chars(reply.data(), reply.data() + reply.size(), v);
    if (reply.empty() || r.ec != std::errc() || r.ptr != reply.data() + reply.size() ||
        !std::isfinite(v))
        return std::nullopt;
    return v;
}

std::optional<bool> parse_flag(std::string_view reply) {
    reply = trim(reply);
    if (reply == "0") return false;
    if (reply == "1") return true;
    return std::nullopt;
}

std::optional<ErrorEntry> parse_error(std::string_view reply) {
    reply = trim(reply);
    const auto comma = reply.find(',');
    if (comma == std::string_view::npos) return std::nullopt;
    const std::string_view code_text = reply.substr(0, comma);
    std::string_view message = trim(reply.substr(comma + 1));
    ErrorEntry e;
    const auto r = std::from_chars(code_text.data(), code_text.data() + code_text.size(), e.code);
    if (code_text.empty() || r.ec != std::errc() || r.ptr != code_text.data() + code_text.size())
        return std::nullopt;
    if (message.size() < 2 || message.front() != '"' || message.back() != '"') return std::nullopt;
    e.message = std::string(message.substr(1, message.size() - 2));
    return e;
}

std::string format_error(const ErrorEntry& entry) {
    return fmt::format("{},\"{}\"", entry.code, entry.message);
}

std::optional<Identity> parse_identity(std::string_view reply) {
    reply = trim(reply);
    std::array<std::string, 4> fields;
    std::size_t start = 0;
    for (std::size_t i = 0; i < fields.size(); ++i) {
        const auto comma = reply.find(',', start);
        if ((comma == std::string_view::npos) != (i == fields.size() - 1)) return std::nullopt;
        fields[i] = std::string(trim(reply.substr(
            start, comma == std::string_view::npos ? std::string_view::npos : comma - start)));
        if (fields[i].empty()) return std::nullopt;
        start = comma + 1;
    }
    const bool printable =
        std::all_of(reply.begin(), reply.end(), [](char c) { return c >= 0x20 && c < 0x7f; });
    if (!printable) return std::nullopt;
    return Identity{fields[0], fields[1], fields[2], fields[3]};
}

}  // namespace tirpol::acquisition::fluke_scpi
