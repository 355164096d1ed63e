#pragma once
/// \file config.h
/// YAML configuration with typed accessors and errors that name the file, line, column, the field's
/// full path, the value found and what was expected. Loaders call `check_keys` on every mapping so
/// that a typo ("camra:") is reported instead of silently ignored.

#include <filesystem>
#include <initializer_list>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace YAML {
class Node;
}

namespace tirpol {

class ConfigNode {
public:
    /// Parses a YAML file. Throws tirpol::Error for a missing file or a syntax error (with line).
    static ConfigNode load_file(const std::filesystem::path& path);
    /// Parses YAML text; `source_name` stands in for the file name in messages.
    static ConfigNode parse(std::string_view text, std::string source_name = "<string>");

    bool is_map() const;
    bool is_sequence() const;
    bool is_scalar() const;
    bool is_null() const;
    bool has(std::string_view key) const;

    /// Required child; error "missing field" naming the parent's location otherwise.
    ConfigNode at(std::string_view key) const;
    std::optional<ConfigNode> find(std::string_view key) const;
    /// Elements of a sequence (error if not a sequence).
    std::vector<ConfigNode> elements() const;
    /// Keys of a mapping in file order (error if not a mapping).
    std::vector<std::string> keys() const;

    /// This node converted to T: double, int, bool, std::string, std::vector<double>,
    /// std::vector<std::string>. Error names the value found and the type expected.
    template <typename T>
    T as() const;

    /// Required field of type T.
    template <typename T>
    T get(std::string_view key) const {
        return at(key).as<T>();
    }
    /// Optional field of type T, `fallback` when absent.
    template <typename T>
    T get_or(std::string_view key, T fallback) const {
        auto child = find(key);
        return child ? child->as<T>() : fallback;
    }
    /// A number that must lie in [lo, hi]; error names the range.
    double get_in_range(std::string_view key, double lo, double hi) const;

    /// Reports the first key not in `allowed`, suggesting the closest allowed one.
    void check_keys(std::initializer_list<std::string_view> allowed) const;
    void check_keys(const std::vector<std::string>& allowed) const;

    /// A deep copy of this node with the node at `path` replaced by a copy of `value` (a sweep
    /// point's scene is its base scene with such overrides, read by the one scene loader). `path`
    /// is keys joined by '.', a list element written `[index]` or `[name]` (the element whose
    /// `name` field is name), e.g. "objects[ball].transform.translate". Every step must exist: an
    /// unknown key throws tirpol::Error naming the step and the closest existing key ("did you
    /// mean"). Locations of the copied value keep their own lines; the copy keeps this node's file
    /// (relative paths still resolve).
    ConfigNode with_value(std::string_view path, const ConfigNode& value) const;

    /// "file.yaml:12:5" of this node.
    std::string location() const;
    /// Dotted path of this node from the root, e.g. "camera.fov_deg" or "objects[2].material".
    const std::string& path() const { return m_path; }
    const std::filesystem::path& file() const;
    /// Resolves a path written in the config relative to the config file's directory.
    std::filesystem::path resolve_path(const std::string& relative) const;

    /// Throws tirpol::Error "<location>: <path>: <message>".
    [[noreturn]] void fail(const std::string& message) const;

    ConfigNode(const ConfigNode&);
    ConfigNode& operator=(const ConfigNode&);
    ConfigNode(ConfigNode&&) noexcept;
    ConfigNode& operator=(ConfigNode&&) noexcept;
    ~ConfigNode();

private:
    struct Source;
    ConfigNode(std::shared_ptr<const Source> source, std::unique_ptr<YAML::Node> node,
               std::string path);
    std::string child_path(std::string_view key) const;

    std::shared_ptr<const Source> m_source;
    std::unique_ptr<YAML::Node> m_node;
    std::string m_path;
};

/// Closest string in `candidates` to `word` by edit distance (for "did you mean" hints); empty if
/// none is close.
std::string closest_match(std::string_view word, const std::vector<std::string>& candidates);

}  // namespace tirpol
