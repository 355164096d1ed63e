#pragma once
/// \file analyzer.h
/// The analyzer (rotating wire-grid polarizer) model and the data-reduction matrix (DRM).
///
/// Measurement at analyzer position k: I_k = t_k · a_k · S + b_k with S = (S0, S1, S2) in the
/// camera frame of ARCHITECTURE.md (0° along image rows, angles counter-clockwise looking at the
/// scene) and the analyzer row a_k = ½·(1, d_k·cos 2θ_k, d_k·sin 2θ_k): the top row of a linear
/// diattenuator's Mueller matrix normalised to its mean transmission (Chipman, Lam & Young 2018,
/// eq 6.35). θ_k is the actual transmission-axis angle, d_k = (t_max − t_min)/(t_max + t_min) the
/// diattenuation ((1 + d)/(1 − d) is the extinction ratio). t_k is the transmission relative to an
/// ideal polarizer (t_max + t_min) and b_k an additive background. For an ideal polarizer
/// (d = 1, t = 1, b = 0) at 0/45/90/135° the DRM W⁺ is exactly the paper's eqs 14–16.
///
/// Data reduction for any N ≥ 3 positions: S = W⁺·I with W the N×3 matrix of rows a_k and W⁺ its
/// Moore–Penrose pseudo-inverse (Tyo, Goldstein, Chenault & Shaw, "Review of passive imaging
/// polarimetry for remote sensing applications", Appl. Opt. 45, 5453–5469, 2006, §4).
///
/// The analyzer model from a polarizer's datasheet, for a polarimetric calibration without
/// known-source records: the extinction ratio and the transmission-axis offsets of the mount.

#include <Eigen/Core>
#include <string>
#include <vector>

namespace tirpol::calibration {

/// Model of one analyzer position.
struct AnalyzerPosition {
    double nominal_angle_deg = 0.0;      ///< the angle the stage was commanded to
    double axis_angle_deg = 0.0;         ///< fitted transmission-axis angle θ_k
    double diattenuation = 1.0;          ///< d_k in [0, 1]
    double relative_transmission = 1.0;  ///< t_k (t_max + t_min; 1 for an ideal polarizer)
    double background = 0.0;             ///< b_k, in the units of the measurements

    /// Extinction ratio t_max/t_min = (1 + d)/(1 − d) (infinite for d = 1).
    double extinction_ratio() const;
    /// The normalised analyzer row ½·(1, d cos 2θ, d sin 2θ).
    Eigen::RowVector3d row() const;
};

struct AnalyzerModel {
    std::vector<AnalyzerPosition> positions;

    /// An ideal polarizer at the given angles (d = 1, t = 1, b = 0).
    static AnalyzerModel ideal(const std::vector<double>& angles_deg);
    /// A polarizer with the given extinction ratio and angle offset (axis = nominal + offset) at
    /// every position, t = t_max + t_min for a major transmittance `t_max`.
    static AnalyzerModel non_ideal(const std::vector<double>& angles_deg, double extinction_ratio,
                                   double angle_offset_deg, double t_max = 1.0);

    /// W: N×3 matrix of the normalised rows.
    Eigen::MatrixX3d measurement_matrix() const;
    /// The data-reduction matrix W⁺ (3×N). Throws tirpol::Error if fewer than 3 positions or if W
    /// is rank-deficient (e.g. angles 0° and 180° only), naming the angles.
    Eigen::Matrix3Xd data_reduction_matrix() const;
    /// Condition number of W (1/√2·… ; the smallest for equally spaced angles).
    double condition_number() const;
};

/// One calibration measurement of a known polarized source: the source Stokes vector (S0, S1, S2)
/// in the camera frame, and the mean measurement at every analyzer position (same order as angles).
struct KnownSourceMeasurement {
    Eigen::Vector3d source_stokes;
    std::vector<double> intensities;
};

/// Least-squares estimate of the analyzer model from measurements of known sources: for every
/// position k, the linear model I_kj = w_k·S_j + b_k is fitted over the sources j, then
/// t_k = 2·w_k0, d_k = |(w_k1, w_k2)|/w_k0, θ_k = ½·atan2(w_k2, w_k1). Needs ≥ 4 sources spanning
/// (S0, S1, S2, 1) — at least two source intensities and two polarization orientations; throws
/// tirpol::Error naming what is missing otherwise.
AnalyzerModel estimate_analyzer(const std::vector<double>& nominal_angles_deg,
                                const std::vector<KnownSourceMeasurement>& measurements);

struct DatasheetAnalyzer {
    double extinction_ratio = 0.0;  ///< t_max/t_min > 1 (e.g. 100–300 for an LWIR wire grid)
    std::vector<double>
        axis_offsets_deg;  ///< axis − nominal: none (0°), one for all, or one per angle
};

/// The model at `angles_deg` (ascending): d = (ER − 1)/(ER + 1), θ_k = nominal_k + offset_k, t = 1
/// + 1/ER. Throws tirpol::Error for ER ≤ 1 or not finite, offsets of another count than 0, 1 or the
/// number of angles (naming both), or an offset of 45° or more.
AnalyzerModel datasheet_analyzer_model(const std::vector<double>& angles_deg,
                                       const DatasheetAnalyzer& datasheet);

/// "datasheet (extinction ratio 150, axis offsets +1.50°)", for the calibration's analyzer method.
std::string describe(const DatasheetAnalyzer& datasheet);

}  // namespace tirpol::calibration
