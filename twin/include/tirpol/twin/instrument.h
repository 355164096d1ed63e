#pragma once
/// \file instrument.h
/// The twin's field instrument: what is in front of the camera (the rendered scene or the
/// blackbody, the polarizer in or out of the beam), the renderer's sensor model as the camera's
/// detector, a stage decorator that tells the world where the polarizer is, and the devices
/// themselves — tirpol-stage-sim's engine on a pseudo-terminal opened through the real serial
/// driver, and the camera served over GigE Vision on loopback (acquisition's fake GigE server)
/// opened as aravis://. The simulators are acquisition internals: only twin/src sees them
/// (TwinInstrument's pimpl), so this header needs nothing but acquisition's public API.

#include <array>
#include <cstdint>
#include <deque>
#include <filesystem>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "tirpol/acquisition/capture.h"
#include "tirpol/acquisition/capture_plan.h"
#include "tirpol/acquisition/stage.h"
#include "tirpol/core/image.h"
#include "tirpol/core/radiometry.h"
#include "tirpol/simulation/dofp_sensor.h"
#include "tirpol/simulation/sensor_model.h"

namespace tirpol::twin {

/// The instrument's detector and wire grid: an uncooled 16-bit camera with NEDT 50 mK, the paper's
/// grid (extinction 400, τ = 0.7, §3.1) tilted so it reflects the cold sky into the camera, and its
/// own emission at air temperature.
simulation::SensorModel twin_sensor(const Band& band, double air_temperature_k);

/// The reference wire-grid polarizer of a microgrid camera's flat-field rig (in front of the
/// blackbody, on the stage): a linear diattenuator of major transmittance `transmission` and
/// extinction ratio `extinction_ratio`, which adds its own unpolarized emission and reflection of
/// the room, `emitted_radiance` (W/(m²·sr)), whatever its angle.
struct ReferencePolarizer {
    double transmission = 0.85;
    double extinction_ratio = 1000.0;
    double emitted_radiance = 1.5;
    /// Its diattenuation (τ − τ_min)/(τ + τ_min), what its datasheet gives the calibration.
    double diattenuation() const { return (extinction_ratio - 1.0) / (extinction_ratio + 1.0); }
};

/// The world the camera looks at. Thread-safe: the camera's fill runs on the server's thread.
class TwinWorld {
public:
    TwinWorld(simulation::SensorModel sensor, Band band, int width, int height);
    /// A microgrid (DoFP) camera's world: the detector is `dofp` (its size is the camera's), and
    /// the polarizer on the stage is the flat-field rig's `reference`, seen only while a backdrop
    /// blackbody is set (set_flat_field_backdrop); scenes are seen without it.
    TwinWorld(simulation::DofpSensor dofp, ReferencePolarizer reference, Band band);

    /// The rendered Stokes image (S0 S1 S2 S3, camera frame) of the current view.
    void set_scene(Image stokes);
    void set_polarizer_in_beam(bool in_beam);
    /// The operator puts the blackbody at `temperature_k` in front of the camera for the next step.
    void place_blackbody(double temperature_k);
    /// The stage starts a move: a blackbody placed for this step stays; otherwise the operator has
    /// taken it away and the camera sees the scene.
    void on_stage_move();
    /// The stage driver reported the move complete: a new stay, whose kept frames take the noise
    /// realisations numbered from its first (take).
    void on_stage_arrived();
    /// Microgrid world: the flat-field rig's blackbody at `temperature_k` fills the view behind
    /// the reference polarizer (the polarizer records of a flat-field session); nullopt: the scene.
    /// A blackbody placed by the operator (place_blackbody) is held in front of the lens and seen
    /// open.
    void set_flat_field_backdrop(std::optional<double> temperature_k);
    /// The microgrid camera's analyzer pattern (degrees, cells (0,0) (0,1) (1,0) (1,1)); nullopt
    /// for the rotating-polarizer instrument.
    std::optional<std::array<double, 4>> microgrid_pattern_deg() const;
    /// The DoFP detector, or nullptr for the rotating-polarizer instrument.
    const simulation::DofpSensor* dofp() const { return m_dofp ? &*m_dofp : nullptr; }
    /// The polarizer angle the stage driver last read back.
    void set_angle_deg(double angle_deg);
    double angle_deg() const;

    /// Counts of one frame at polarizer angle `angle_deg` whose exposure ended at
    /// `exposure_end_ns` (CLOCK_REALTIME), as the camera sends them: the sensor model (gain,
    /// offset, NEDT noise, the grid's reflected and emitted radiance) with a noise realisation of
    /// the exposure's own (its place in the stay). The world remembers the exposure (the angle and
    /// what was in view) for take(). Frames are filled in the order of their exposure.
    void fill(double angle_deg, std::vector<float>& counts, std::int64_t exposure_end_ns);
    /// fill() of a frame whose exposure ends now.
    void fill(double angle_deg, std::vector<float>& counts);
    /// The capture loop took the frame whose counts arrived as `counts`, the first exposure filled
    /// at or after `exposure_end_ns`: checks that its mean is the one the camera sent (within the
    /// ADC's rounding), and redraws its noise with the realisation of the stay's next kept frame —
    /// numbered by the frames the loop's gate kept (frame_kept), so a step averages the same
    /// realisations whichever frames the camera delivered before and whichever the gate discarded.
    /// Throws tirpol::Error when no such exposure was filled or the mean differs.
    void take(std::int64_t exposure_end_ns, std::vector<float>& counts);
    /// The capture loop's gate kept the frame taken last.
    void frame_kept();

    /// Counts of one frame of `stokes` through the same sensor model, polarizer at `angle_deg` or
    /// out of the beam, noise realisation `frame_index` (frames filmed outside the capture loop,
    /// e.g. of the geometric calibration target).
    std::vector<float> sensor_frame(const Image& stokes, double angle_deg, bool polarizer_in_beam,
                                    std::uint64_t frame_index) const;

    int width() const { return m_width; }
    int height() const { return m_height; }
    /// The instrument's sensor model (what its datasheets tell the user).
    const simulation::SensorModel& sensor() const { return m_sensor; }

private:
    const Image& blackbody_image(double temperature_k);
    /// What a frame saw over its exposure, and the mean counts the camera sent of it.
    struct Exposure {
        std::int64_t end_ns = 0;
        double angle_deg = 0.0;
        std::optional<double> blackbody_k, backdrop_k;
        bool polarizer_in_beam = true;
        double sent_mean = 0.0;
    };
    /// Realisations are 2³⁰ + stay·2¹² + place (place < 2¹¹: the stay's kept frames, from 2¹¹: the
    /// frames as sent); below 2³⁰ are the frames filmed outside the capture loop (sensor_frame's
    /// callers).
    std::uint64_t realisation(std::uint64_t place) const;                         ///< m_mutex held
    std::vector<float> render(const Exposure& e, std::uint64_t realisation);      ///< m_mutex held
    std::vector<float> dofp_frame(const Exposure& e, std::uint64_t realisation);  ///< m_mutex held

    std::optional<simulation::DofpSensor> m_dofp;
    ReferencePolarizer m_reference;
    std::optional<double> m_backdrop_k;

    mutable std::mutex m_mutex;
    simulation::SensorModel m_sensor;
    Band m_band;
    int m_width, m_height;
    Image m_scene;
    std::map<long, Image> m_blackbodies;  ///< by temperature in mK
    bool m_polarizer_in_beam = true;
    std::optional<double> m_pending_blackbody_k, m_blackbody_k;
    double m_angle_deg = 0.0;
    std::uint64_t m_stay = 0;  ///< completed moves
    std::uint64_t m_sent_in_stay = 0, m_kept_in_stay = 0;
    std::deque<Exposure> m_exposures;  ///< filled and not yet taken, oldest first
};

/// A Stage that forwards to the real driver and reports every move and read-back to the world, so
/// the camera renders the polarizer where the driver says it is (never where the plan wants it).
class WorldReportingStage final : public acquisition::Stage {
public:
    WorldReportingStage(acquisition::Stage& inner, TwinWorld& world)
        : m_inner(inner), m_world(world) {}
    acquisition::StageInfo info() const override { return m_inner.info(); }
    acquisition::Status home(std::chrono::milliseconds timeout) override;
    bool is_homed() const override { return m_inner.is_homed(); }
    acquisition::Status move_absolute(double angle_deg, std::chrono::milliseconds timeout) override;
    acquisition::Result<double> position_deg() override;

private:
    acquisition::Stage& m_inner;
    TwinWorld& m_world;
};

/// The byte protocol the simulated polarizer mount speaks on its pseudo-terminal.
enum class StageProtocol {
    Apt,       ///< Thorlabs APT (K10CR1), opened as thorlabs-apt://
    Elliptec,  ///< Thorlabs Elliptec (ELL14), opened as elliptec://
};

/// The devices of the twin. Throws tirpol::Error when the stage cannot be opened; a GigE Vision
/// failure falls back to the in-process SimulatedCamera and says why in `camera_transport()`.
class TwinInstrument {
public:
    /// `genicam_xml`: the fake GigE camera's GenICam XML, which must offer PolarizeMono16 for a
    /// microgrid world (tests/data/genicam/polarized-fake-camera.xml); empty: Aravis's built-in
    /// one, and a microgrid world falls back to the in-process camera.
    TwinInstrument(TwinWorld& world, StageProtocol protocol, bool gige,
                   std::filesystem::path genicam_xml = {});
    ~TwinInstrument();
    TwinInstrument(const TwinInstrument&) = delete;
    TwinInstrument& operator=(const TwinInstrument&) = delete;

    /// "GigE Vision on 127.0.0.1 (aravis://…)" or "in-process SimulatedCamera (FALLBACK: <why>)".
    const std::string& camera_transport() const;
    std::string stage_description() const;
    bool served_over_gige() const;

    /// Runs `plan` (the library call behind `tirpol acquire`) into a new session at `dir`; the
    /// simulated operator places the blackbody when the capture loop asks for it. Returns the
    /// capture's summary (frames, drops, delivered frame rate).
    acquisition::CaptureSummary acquire(const acquisition::CapturePlan& plan,
                                        const std::filesystem::path& dir);

private:
    struct Devices;  ///< the stage simulator on its pty, the drivers, the fake GigE server
                     ///< (twin/src)
    std::unique_ptr<Devices> m_devices;
};

}  // namespace tirpol::twin
