#pragma once
// RAII for Aravis's GObject C API and the translation of GError into DeviceError (STYLE.md: every
// error keeps its domain and code). Private to the acquisition module.

#include <arv.h>

#include <memory>
#include <string>

#include "tirpol/acquisition/result.h"

namespace tirpol::acquisition::aravis {

/// Owns one GObject reference; g_object_unref on destruction.
struct GObjectUnref {
    void operator()(gpointer object) const {
        if (object != nullptr) g_object_unref(object);
    }
};
template <typename T>
using GObjectPtr = std::unique_ptr<T, GObjectUnref>;

/// A GError out-parameter that frees itself: `GErrorSlot e; f(..., e.out()); if (e) ...`.
class GErrorSlot {
public:
    GErrorSlot() = default;
    GErrorSlot(const GErrorSlot&) = delete;
    GErrorSlot& operator=(const GErrorSlot&) = delete;
    ~GErrorSlot() { g_clear_error(&m_error); }
    GError** out() {
        g_clear_error(&m_error);
        return &m_error;
    }
    explicit operator bool() const { return m_error != nullptr; }
    const GError* get() const { return m_error; }

private:
    GError* m_error = nullptr;
};

/// A g_free'd array of strings as Aravis's dup_* functions return (the strings themselves are not
/// owned).
struct GFree {
    void operator()(gpointer p) const { g_free(p); }
};

/// Maps a GError from Aravis (ArvDeviceError, ArvGcError, GIOError) to a DeviceError whose message
/// names the device, the action, the GError message, its domain and its code.
DeviceError to_device_error(const GError* error, const std::string& device,
                            const std::string& action);

}  // namespace tirpol::acquisition::aravis
