#pragma once
// The table behind register_camera_scheme / register_stage_scheme: URI scheme → factory, safe to
// use from several threads. Private to the acquisition module.

#include <fmt/format.h>

#include <map>
#include <mutex>
#include <string>
#include <utility>
#include <vector>

#include "tirpol/core/error.h"

namespace tirpol::acquisition::detail {

template <typename Factory>
class SchemeRegistry {
public:
    /// Adds or replaces the factory of `scheme`; returns the replaced one (empty if none). Throws
    /// tirpol::Error, naming `caller`, for a name that is not a URI scheme or an empty factory.
    Factory register_scheme(const std::string& scheme, Factory factory,
                            const char* caller = "register_scheme") {
        if (scheme.empty() || scheme.find_first_of(":/?") != std::string::npos)
            fail("{}: '{}' is not a URI scheme (expected a name without ':', '/' or '?')", caller,
                 scheme);
        if (!factory) fail("{}: empty factory for scheme '{}'", caller, scheme);
        std::lock_guard lock(m_mutex);
        Factory& slot = m_factories[scheme];
        return std::exchange(slot, std::move(factory));
    }

    /// The factory of `scheme`, or an empty one.
    Factory find(const std::string& scheme) const {
        std::lock_guard lock(m_mutex);
        const auto it = m_factories.find(scheme);
        return it == m_factories.end() ? Factory{} : it->second;
    }

    /// The registered schemes, sorted.
    std::vector<std::string> schemes() const {
        std::lock_guard lock(m_mutex);
        std::vector<std::string> names;
        for (const auto& entry : m_factories) names.push_back(entry.first);
        return names;
    }

    /// "unknown <kind> scheme 'x' in '<uri>' (known schemes: a, b, c)".
    std::string unknown_scheme_message(const char* kind, const std::string& scheme,
                                       const std::string& uri) const {
        return fmt::format("device URI '{}': unknown {} scheme '{}' (known schemes: {})", uri, kind,
                           scheme, fmt::join(schemes(), ", "));
    }

private:
    mutable std::mutex m_mutex;
    std::map<std::string, Factory> m_factories;
};

}  // namespace tirpol::acquisition::detail
