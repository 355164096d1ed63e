#pragma once
/// \file solver_termination.h
/// How a least-squares solve ended, as a type: Ceres' termination type (without Ceres in the
/// header) and its message. Written out as Ceres spells it ("CONVERGENCE: …") in the fit's JSON
/// and text report, so those files do not change.

#include <fmt/format.h>

#include <ostream>
#include <string>
#include <string_view>

namespace tirpol::fitting {

struct SolverTermination {
    /// ceres::TerminationType, plus NotRun for a result no solve has filled in yet.
    enum class Type { NotRun, Convergence, NoConvergence, Failure, UserSuccess, UserFailure };
    Type type = Type::NotRun;
    std::string message;  ///< ceres::Solver::Summary::message

    /// "TYPE: message" (Ceres' TerminationTypeToString spelling); empty for NotRun.
    std::string text() const;
};

/// "NOT_RUN", "CONVERGENCE", "NO_CONVERGENCE", "FAILURE", "USER_SUCCESS", "USER_FAILURE".
std::string_view to_string(SolverTermination::Type type);

/// Writes text() (for test failure messages).
std::ostream& operator<<(std::ostream& out, const SolverTermination& termination);

}  // namespace tirpol::fitting

/// Formats as text(), so messages keep reading "CONVERGENCE: …".
template <>
struct fmt::formatter<tirpol::fitting::SolverTermination> : fmt::formatter<std::string> {
    template <typename FormatContext>
    auto format(const tirpol::fitting::SolverTermination& t, FormatContext& ctx) const {
        return fmt::formatter<std::string>::format(t.text(), ctx);
    }
};
