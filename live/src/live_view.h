#pragma once
/// \file live_view.h
/// Everything `tirpol live` shows and does, without the HTTP: the devices opened by URI, the grab
/// thread (FrameFeed), the display conversion, the polarizer cycle (with a stage) and the capture
/// control, plus the encoded images and status the page polls.

#include <memory>
#include <mutex>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "capture_control.h"
#include "display_frame.h"
#include "frame_feed.h"
#include "polarizer_cycle.h"
#include "region_statistics.h"
#include "tirpol/acquisition/camera.h"
#include "tirpol/acquisition/stage.h"
#include "tirpol/calibration/microgrid_stokes.h"
#include "tirpol/calibration/radiometric.h"
#include "tirpol/live/live_server.h"

namespace tirpol::live {

/// An encoded image and the LatestSlot sequence it came from.
struct EncodedImage {
    std::uint64_t sequence = 0;
    std::shared_ptr<const std::string> bytes;  ///< null: nothing newer than asked for
};

class LiveView {
public:
    /// Validates the options, opens the devices and the calibration and starts streaming (and
    /// cycling, with a stage). Throws tirpol::Error naming the option, URI or file that failed.
    explicit LiveView(const LiveViewOptions& options);
    ~LiveView();
    LiveView(const LiveView&) = delete;
    LiveView& operator=(const LiveView&) = delete;

    /// The latest S0 frame once newer than `after`, waiting at most `timeout`. Each frame is
    /// encoded once however many pages ask for it.
    EncodedImage frame_after(std::uint64_t after, std::chrono::milliseconds timeout);
    /// The latest cycle's S0 S1 S2 DoLP AoP the same way (never anything without a stage).
    EncodedImage stokes_after(std::uint64_t after, std::chrono::milliseconds timeout);
    /// Camera, statistics, FPA history, stage and capture state as JSON (docs/live.md lists the
    /// fields).
    nlohmann::json status() const;
    /// The region readout (region_statistics.h) over the latest S0 frame and the latest cycle.
    /// Throws tirpol::Error for a region outside the image or a bad threshold, or when there is no
    /// frame yet.
    nlohmann::json region(const PixelRegion& region, double dolp_min) const;
    /// Static facts for the page: camera, units, whether a stage is present, the capture form
    /// defaults.
    nlohmann::json describe() const;

    /// Writes the latest frame (and the latest cycle's Stokes, with a stage) into the snapshot
    /// folder: `snapshot-TIME-N.exr` with the float channels (S0 S1 S2 DoLP AoP and their _std
    /// from the cycle and the live frame's `live_S0`, or `S0` alone without a stage) and header
    /// attributes time_utc, camera_*, frame_id, cycle_frame_ids, analyzer_angles_deg, units; and
    /// a PNG quick look per channel with the same metadata. Returns {"files": [...], "folder"}.
    /// Throws tirpol::Error without a snapshot folder, before the first frame, or when a file
    /// exists (without force).
    nlohmann::json snapshot();

    bool has_stage() const { return m_stage != nullptr; }
    /// Whether the Stokes images come from single microgrid frames (a microgrid camera, no stage).
    bool has_microgrid() const { return m_microgrid.has_value(); }
    /// The capture control; throws tirpol::Error without a stage.
    CaptureControl& capture();

private:
    struct Cache {
        std::mutex mutex;
        EncodedImage image;
    };
    template <typename T, typename Encode>
    EncodedImage encoded_after(const LatestSlot<T>& slot, Cache& cache, std::uint64_t after,
                               std::chrono::milliseconds timeout, Encode encode);

    /// S0 S1 S2 DoLP AoP of one microgrid frame (reduce_microgrid), with its frame id.
    Image microgrid_stokes(const acquisition::Frame& frame) const;
    /// The Stokes image the page shows now: the latest cycle, or the latest microgrid frame's.
    std::shared_ptr<const Image> latest_stokes() const;

    LiveViewOptions m_options;
    std::optional<calibration::MicrogridPattern> m_microgrid;
    calibration::DemosaicMethod m_demosaic = calibration::DemosaicMethod::Bilinear;
    std::unique_ptr<acquisition::Camera> m_camera;
    std::unique_ptr<acquisition::Stage> m_stage;
    std::optional<calibration::RadiometricCalibration> m_calibration;
    std::unique_ptr<DisplayConverter> m_converter;
    std::unique_ptr<FrameFeed> m_feed;
    std::unique_ptr<PolarizerCycle> m_cycle;
    std::unique_ptr<CaptureControl> m_capture;
    Cache m_frame_cache, m_stokes_cache;
    std::mutex m_snapshot_mutex;  ///< one snapshot at a time (numbered in order)
    int m_snapshots = 0;
};

}  // namespace tirpol::live
