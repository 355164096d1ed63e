#include "tirpol/report/provenance.h"

#include <fmt/format.h>

#include "tirpol/core/atomic_file.h"

namespace tirpol::report {

std::string attribute_text(const AttributeValue& value) {
    return std::visit(
        [](const auto& x) -> std::string {
            using T = std::decay_t<decltype(x)>;
            if constexpr (std::is_same_v<T, std::string>) {
                return x;
            } else if constexpr (std::is_same_v<T, std::vector<double>>) {
                std::string out = "[";
                for (std::size_t i = 0; i < x.size(); ++i)
                    out += fmt::format("{}{:.10g}", i ? ", " : "", x[i]);
                return out + "]";
            } else if constexpr (std::is_same_v<T, double>) {
                return fmt::format("{:.10g}", x);
            } else {
                return fmt::format("{}", x);
            }
        },
        value);
}

InputFile describe_input(const std::string& role, const std::filesystem::path& path,
                         const Image* header) {
    InputFile file;
    file.role = role;
    file.path = path;
    const std::string bytes = read_file(path);
    file.sha256 = sha256_hex(bytes);
    file.size_bytes = bytes.size();
    if (header)
        for (const auto& [name, value] : header->attributes())
            file.attributes.emplace_back(name, attribute_text(value));
    return file;
}

std::filesystem::path path_relative_to(const std::filesystem::path& file,
                                       const std::filesystem::path& dir) {
    std::error_code error;
    const auto absolute_file =
        std::filesystem::weakly_canonical(std::filesystem::absolute(file), error);
    if (error) return file;
    const auto absolute_dir =
        std::filesystem::weakly_canonical(std::filesystem::absolute(dir), error);
    if (error) return absolute_file;
    const auto relative = absolute_file.lexically_relative(absolute_dir);
    return relative.empty() ? absolute_file : relative;
}

std::string quoted_command_line(int argc, const char* const* argv) {
    std::string line;
    for (int i = 0; i < argc; ++i) {
        const std::string_view arg = argv[i];
        const bool plain =
            !arg.empty() && arg.find_first_not_of(
                                "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ"
                                "0123456789-_./=:,+@%") == std::string_view::npos;
        if (i) line += ' ';
        if (plain) {
            line += arg;
            continue;
        }
        line += '\'';
        for (char c : arg) line += c == '\'' ? std::string("'\\''") : std::string(1, c);
        line += '\'';
    }
    return line;
}

}  // namespace tirpol::report
