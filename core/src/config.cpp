#include "tirpol/core/config.h"

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <unordered_map>
#include <unordered_set>
#include <utility>

#include "tirpol/core/atomic_file.h"
#include "tirpol/core/error.h"
#include "tirpol/core/output_guard.h"

namespace tirpol {

struct ConfigNode::Source {
    std::filesystem::path file;
    std::string display_name;
};

ConfigNode::ConfigNode(std::shared_ptr<const Source> source, std::unique_ptr<YAML::Node> node,
                       std::string path)
    : m_source(std::move(source)), m_node(std::move(node)), m_path(std::move(path)) {}
ConfigNode::ConfigNode(const ConfigNode& o)
    : m_source(o.m_source), m_node(std::make_unique<YAML::Node>(*o.m_node)), m_path(o.m_path) {}
ConfigNode& ConfigNode::operator=(const ConfigNode& o) {
    if (this != &o) {
        m_source = o.m_source;
        m_node = std::make_unique<YAML::Node>(*o.m_node);
        m_path = o.m_path;
    }
    return *this;
}
ConfigNode::ConfigNode(ConfigNode&&) noexcept = default;
ConfigNode& ConfigNode::operator=(ConfigNode&&) noexcept = default;
ConfigNode::~ConfigNode() = default;

namespace {
std::string describe(const YAML::Node& node) {
    switch (node.Type()) {
        case YAML::NodeType::Null:
            return "nothing (null)";
        case YAML::NodeType::Sequence:
            return "a list";
        case YAML::NodeType::Map:
            return "a mapping";
        case YAML::NodeType::Scalar:
            return "'" + node.Scalar() + "'";
        default:
            return "an undefined value";
    }
}

// yaml-cpp keeps every pair of a mapping and its lookups return the first: a repeated key would be
// silently dropped. Each collection is visited once (aliases share nodes, so a YAML bomb stays
// linear).
void check_unique_keys(const YAML::Node& node, const std::string& source,
                       std::unordered_set<std::size_t>& visited) {
    if (!node.IsMap() && !node.IsSequence()) return;
    if (!visited.insert(static_cast<std::size_t>(node.Mark().pos)).second) return;
    if (node.IsSequence()) {
        for (const auto& element : node) check_unique_keys(element, source, visited);
        return;
    }
    std::unordered_map<std::string, YAML::Mark> seen;
    for (const auto& kv : node) {
        if (kv.first.IsScalar()) {
            const auto [it, inserted] = seen.emplace(kv.first.Scalar(), kv.first.Mark());
            if (!inserted)
                tirpol::fail(
                    "{}:{}:{}: duplicate key '{}' (first given at {}:{}:{}); each key may appear "
                    "once in a mapping",
                    source, kv.first.Mark().line + 1, kv.first.Mark().column + 1, kv.first.Scalar(),
                    source, it->second.line + 1, it->second.column + 1);
        }
        check_unique_keys(kv.second, source, visited);
    }
}
}  // namespace

ConfigNode ConfigNode::parse(std::string_view text, std::string source_name) {
    auto source = std::make_shared<Source>(Source{source_name, source_name});
    check_utf8_text(text, source_name);
    try {
        auto node = std::make_unique<YAML::Node>(YAML::Load(std::string(text)));
        std::unordered_set<std::size_t> visited;
        check_unique_keys(*node, source_name, visited);
        return ConfigNode(std::move(source), std::move(node), "");
    } catch (const YAML::Exception& e) {
        tirpol::fail("{}:{}:{}: YAML syntax error: {}", source_name, e.mark.line + 1,
                     e.mark.column + 1, e.msg);
    }
}

ConfigNode ConfigNode::load_file(const std::filesystem::path& path) {
    const std::string text = read_file(path);
    auto node = parse(text, path.string());
    return node;
}

bool ConfigNode::is_map() const { return m_node->IsMap(); }
bool ConfigNode::is_sequence() const { return m_node->IsSequence(); }
bool ConfigNode::is_scalar() const { return m_node->IsScalar(); }
bool ConfigNode::is_null() const { return m_node->IsNull(); }
bool ConfigNode::has(std::string_view key) const {
    return m_node->IsMap() && static_cast<bool>(std::as_const(*m_node)[std::string(key)]);
}

std::string ConfigNode::child_path(std::string_view key) const {
    return m_path.empty() ? std::string(key) : m_path + "." + std::string(key);
}

std::optional<ConfigNode> ConfigNode::find(std::string_view key) const {
    if (!m_node->IsMap()) {
        if (m_node->IsNull()) return std::nullopt;
        fail(fmt::format("expected a mapping with a field '{}', found {}", key, describe(*m_node)));
    }
    // Const lookup: yaml-cpp's non-const operator[] adds an (undefined) entry for a missing key,
    // allocated in this node's memory; a tree shared with another (with_value) would keep a
    // dangling entry.
    YAML::Node child = std::as_const(*m_node)[std::string(key)];
    if (!child) return std::nullopt;
    return ConfigNode(m_source, std::make_unique<YAML::Node>(child), child_path(key));
}

ConfigNode ConfigNode::at(std::string_view key) const {
    auto child = find(key);
    if (!child) fail(fmt::format("missing required field '{}'", key));
    return *child;
}

std::vector<ConfigNode> ConfigNode::elements() const {
    if (!m_node->IsSequence()) fail("expected a list, found " + describe(*m_node));
    std::vector<ConfigNode> out;
    for (std::size_t i = 0; i < m_node->size(); ++i)
        out.emplace_back(ConfigNode(m_source,
                                    std::make_unique<YAML::Node>(std::as_const(*m_node)[i]),
                                    m_path + "[" + std::to_string(i) + "]"));
    return out;
}

std::vector<std::string> ConfigNode::keys() const {
    if (!m_node->IsMap()) fail("expected a mapping, found " + describe(*m_node));
    std::vector<std::string> out;
    for (const auto& kv : *m_node) out.push_back(kv.first.Scalar());
    return out;
}

template <>
double ConfigNode::as<double>() const {
    double v = 0.0;
    if (!m_node->IsScalar() || !YAML::convert<double>::decode(*m_node, v))
        fail("expected a number, found " + describe(*m_node));
    if (!std::isfinite(v)) fail("expected a finite number, found " + describe(*m_node));
    return v;
}

template <>
int ConfigNode::as<int>() const {
    int v = 0;
    if (!m_node->IsScalar() || !YAML::convert<int>::decode(*m_node, v))
        fail("expected an integer, found " + describe(*m_node));
    return v;
}

template <>
bool ConfigNode::as<bool>() const {
    bool v = false;
    if (!m_node->IsScalar() || !YAML::convert<bool>::decode(*m_node, v))
        fail("expected true or false, found " + describe(*m_node));
    return v;
}

template <>
std::string ConfigNode::as<std::string>() const {
    if (!m_node->IsScalar()) fail("expected a text value, found " + describe(*m_node));
    return m_node->Scalar();
}

template <>
std::vector<double> ConfigNode::as<std::vector<double>>() const {
    std::vector<double> out;
    for (const auto& e : elements()) out.push_back(e.as<double>());
    return out;
}

template <>
std::vector<std::string> ConfigNode::as<std::vector<std::string>>() const {
    std::vector<std::string> out;
    for (const auto& e : elements()) out.push_back(e.as<std::string>());
    return out;
}

double ConfigNode::get_in_range(std::string_view key, double lo, double hi) const {
    auto child = at(key);
    const double v = child.as<double>();
    if (v < lo || v > hi)
        child.fail(
            fmt::format("value {} is out of range: expected a number in [{}, {}]", v, lo, hi));
    return v;
}

void ConfigNode::check_keys(std::initializer_list<std::string_view> allowed) const {
    check_keys(std::vector<std::string>(allowed.begin(), allowed.end()));
}

void ConfigNode::check_keys(const std::vector<std::string>& allowed) const {
    if (m_node->IsNull()) return;
    if (!m_node->IsMap()) fail("expected a mapping, found " + describe(*m_node));
    for (const auto& kv : *m_node) {
        const std::string key = kv.first.Scalar();
        if (std::find(allowed.begin(), allowed.end(), key) != allowed.end()) continue;
        std::string known;
        for (const auto& a : allowed) known += (known.empty() ? "" : ", ") + a;
        const std::string hint = closest_match(key, allowed);
        ConfigNode key_node(m_source, std::make_unique<YAML::Node>(kv.first), child_path(key));
        key_node.fail(fmt::format("unknown key '{}'{} (allowed here: {})", key,
                                  hint.empty() ? "" : " — did you mean '" + hint + "'?", known));
    }
}

namespace {
/// Splits "a.b[c].d" into {"a", "b", "[c]", "d"}; an empty step is an error.
std::vector<std::string> path_steps(std::string_view path) {
    std::vector<std::string> steps;
    std::string current;
    auto flush = [&] {
        if (current.empty())
            tirpol::fail("parameter path '{}': empty step (expected key.key[name].key)", path);
        steps.push_back(current);
        current.clear();
    };
    for (std::size_t i = 0; i < path.size(); ++i) {
        const char c = path[i];
        if (c == '.') {
            if (i == 0 || path[i - 1] != ']') flush();
        } else if (c == '[') {
            if (!current.empty()) flush();
            const std::size_t close = path.find(']', i);
            if (close == std::string_view::npos || close == i + 1)
                tirpol::fail("parameter path '{}': expected [index] or [name] after position {}",
                             path, i);
            steps.emplace_back(path.substr(i, close - i + 1));
            i = close;
        } else {
            current += c;
        }
    }
    if (!current.empty() || path.empty() || path.back() == '.') flush();
    return steps;
}

/// Index of the element of `list` selected by "[2]" or "[ball]" (its `name` field).
std::size_t list_index(const YAML::Node& list, const std::string& step, const std::string& where) {
    const std::string key = step.substr(1, step.size() - 2);
    if (!list.IsSequence())
        tirpol::fail("{}: '{}' selects a list element, but this is {}", where, step,
                     describe(list));
    std::vector<std::string> names;
    for (std::size_t i = 0; i < list.size(); ++i) {
        if (std::to_string(i) == key) return i;
        if (list[i].IsMap() && list[i]["name"] && list[i]["name"].IsScalar()) {
            if (list[i]["name"].Scalar() == key) return i;
            names.push_back(list[i]["name"].Scalar());
        }
    }
    const std::string hint = closest_match(key, names);
    tirpol::fail("{}: no element '{}' in this list of {} (names: {}){}", where, key, list.size(),
                 fmt::join(names, ", "), hint.empty() ? "" : " — did you mean '" + hint + "'?");
}

/// `node` with the node at steps[i…] replaced by `value`. Only the collections along the path are
/// new; every other node (and `value`) is shared, so it keeps its file position for error messages.
YAML::Node replaced(const YAML::Node& node, const std::vector<std::string>& steps, std::size_t i,
                    const YAML::Node& value, const std::string& where) {
    if (i == steps.size()) return value;
    const std::string& step = steps[i];
    const std::string here = where.empty() ? step : where + (step.front() == '[' ? "" : ".") + step;
    if (step.front() == '[') {
        const std::size_t selected =
            list_index(node, step, where.empty() ? "the top level" : where);
        YAML::Node copy(YAML::NodeType::Sequence);
        for (std::size_t k = 0; k < node.size(); ++k)
            copy.push_back(k == selected ? replaced(node[k], steps, i + 1, value, here) : node[k]);
        return copy;
    }
    const std::string parent = where.empty() ? "the top level" : where;
    if (!node.IsMap())
        tirpol::fail("{}: '{}' is a field, but this is {}", parent, step, describe(node));
    std::vector<std::string> keys;
    for (const auto& kv : node) keys.push_back(kv.first.Scalar());
    if (std::find(keys.begin(), keys.end(), step) == keys.end()) {
        const std::string hint = closest_match(step, keys);
        tirpol::fail("{}: no field '{}'{} (fields here: {})", parent, step,
                     hint.empty() ? "" : " — did you mean '" + hint + "'?", fmt::join(keys, ", "));
    }
    YAML::Node copy(YAML::NodeType::Map);
    for (const auto& kv : node)
        copy.force_insert(kv.first, kv.first.Scalar() == step
                                        ? replaced(kv.second, steps, i + 1, value, here)
                                        : kv.second);
    return copy;
}
}  // namespace

ConfigNode ConfigNode::with_value(std::string_view path, const ConfigNode& value) const {
    YAML::Node root = replaced(*m_node, path_steps(path), 0, *value.m_node, m_path);
    return ConfigNode(m_source, std::make_unique<YAML::Node>(root), m_path);
}

std::string ConfigNode::location() const {
    const YAML::Mark mark = m_node->Mark();
    if (mark.is_null() || mark.line < 0) return m_source->display_name;
    return fmt::format("{}:{}:{}", m_source->display_name, mark.line + 1, mark.column + 1);
}

const std::filesystem::path& ConfigNode::file() const { return m_source->file; }

std::filesystem::path ConfigNode::resolve_path(const std::string& relative) const {
    std::filesystem::path p(relative);
    if (p.is_absolute()) return p;
    return m_source->file.parent_path() / p;
}

void ConfigNode::fail(const std::string& message) const {
    if (m_path.empty()) throw Error(fmt::format("{}: {}", location(), message));
    throw Error(fmt::format("{}: {}: {}", location(), m_path, message));
}

std::string closest_match(std::string_view word, const std::vector<std::string>& candidates) {
    auto distance = [](std::string_view a, std::string_view b) {
        std::vector<std::size_t> prev(b.size() + 1), cur(b.size() + 1);
        for (std::size_t j = 0; j <= b.size(); ++j) prev[j] = j;
        for (std::size_t i = 1; i <= a.size(); ++i) {
            cur[0] = i;
            for (std::size_t j = 1; j <= b.size(); ++j)
                cur[j] = std::min(
                    {prev[j] + 1, cur[j - 1] + 1, prev[j - 1] + (a[i - 1] == b[j - 1] ? 0 : 1)});
            std::swap(prev, cur);
        }
        return prev[b.size()];
    };
    std::string best;
    std::size_t best_d = std::max<std::size_t>(2, word.size() / 3) + 1;
    for (const auto& c : candidates) {
        const std::size_t d = distance(word, c);
        if (d < best_d) {
            best_d = d;
            best = c;
        }
    }
    return best;
}

}  // namespace tirpol
