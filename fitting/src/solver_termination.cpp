#include "ceres_termination.h"
#include "tirpol/fitting/microfacet_fit.h"

namespace tirpol::fitting {

std::string_view to_string(SolverTermination::Type type) {
    switch (type) {
        case SolverTermination::Type::NotRun:
            return "NOT_RUN";
        case SolverTermination::Type::Convergence:
            return "CONVERGENCE";
        case SolverTermination::Type::NoConvergence:
            return "NO_CONVERGENCE";
        case SolverTermination::Type::Failure:
            return "FAILURE";
        case SolverTermination::Type::UserSuccess:
            return "USER_SUCCESS";
        case SolverTermination::Type::UserFailure:
            return "USER_FAILURE";
    }
    return "FAILURE";
}

std::string SolverTermination::text() const {
    if (type == Type::NotRun) return {};
    return std::string(to_string(type)) + ": " + message;
}

std::ostream& operator<<(std::ostream& out, const SolverTermination& termination) {
    return out << termination.text();
}

SolverTermination termination_of(const ceres::Solver::Summary& summary) {
    SolverTermination t;
    t.message = summary.message;
    switch (summary.termination_type) {
        case ceres::CONVERGENCE:
            t.type = SolverTermination::Type::Convergence;
            break;
        case ceres::NO_CONVERGENCE:
            t.type = SolverTermination::Type::NoConvergence;
            break;
        case ceres::USER_SUCCESS:
            t.type = SolverTermination::Type::UserSuccess;
            break;
        case ceres::USER_FAILURE:
            t.type = SolverTermination::Type::UserFailure;
            break;
        default:
            t.type = SolverTermination::Type::Failure;
            break;
    }
    return t;
}

}  // namespace tirpol::fitting
