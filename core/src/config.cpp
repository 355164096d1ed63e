#include "tirpol/core/config.h"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <unordered_map>
#include <unordered_set>

#include "tirpol/core/atomic_file.h"
#include "tirpol/core/error.h"

namespace tirpol {

struct ConfigNode::Source {
    std::filesystem::path file;
    std::string display_name;
};

ConfigNode::ConfigNode(std::shared_ptr<const Source> source, std::unique_ptr<YAML::Node> node, std::string path)
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
        case YAML::NodeType::Null: return "nothing (null)";
        case YAML::NodeType::Sequence: return "a list";
        case YAML::NodeType::Map: return "a mapping";
        case YAML::NodeType::Scalar: return "'" + node.Scalar() + "'";
        default: return "an undefined value";
    }
}

// yaml-cpp keeps every pair of a mapping and its lookups return the first: a repeated key would be
// silently dropped. Each collection is visited once (aliases share nodes, so a YAML bomb stays linear).
void check_unique_keys(const YAML::Node& node, const std::string& source, std::unordered_set<std::size_t>& visited) {
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
                    "{}:{}:{}: duplicate key '{}' (first given at {}:{}:{}); each key may appear once in a mapping",
                    source, kv.first.Mark().line + 1, kv.first.Mark().column + 1, kv.first.Scalar(), source,
                    it->second.line + 1, it->second.column + 1);
        }
        check_unique_keys(kv.second, source, visited);
    }
}
}  // namespace

ConfigNode ConfigNode::parse(std::string_view text, std::string source_name) {
    auto source = std::make_shared<Source>(Source{source_name, source_name});
    try {
        auto node = std::make_unique<YAML::Node>(YAML::Load(std::string(text)));
        std::unordered_set<std::size_t> visited;
        check_unique_keys(*node, source_name, visited);
        return ConfigNode(std::move(source), std::move(node), "");
    } catch (const YAML::Exception& e) {
        tirpol::fail("{}:{}:{}: YAML syntax error: {}", source_name, e.mark.line + 1, e.mark.column + 1, e.msg);
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
    return m_node->IsMap() && static_cast<bool>((*m_node)[std::string(key)]);
}

std::string ConfigNode::child_path(std::string_view key) const {
    return m_path.empty() ? std::string(key) : m_path + "." + std::string(key);
}

std::optional<ConfigNode> ConfigNode::find(std::string_view key) const {
    if (!m_node->IsMap()) {
        if (m_node->IsNull()) return std::nullopt;
        fail(fmt::format("expected a mapping with a field '{}', found {}", key, describe(*m_node)));
    }
    YAML::Node child = (*m_node)[std::string(key)];
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
        out.emplace_back(ConfigNode(m_source, std::make_unique<YAML::Node>((*m_node)[i]),
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
    if (v < lo || v > hi) child.fail(fmt::format("value {} is out of range: expected a number in [{}, {}]", v, lo, hi));
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
                cur[j] = std::min({prev[j] + 1, cur[j - 1] + 1, prev[j - 1] + (a[i - 1] == b[j - 1] ? 0 : 1)});
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
