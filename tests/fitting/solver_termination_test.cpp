// SolverTermination: the typed form of Ceres' termination, written out as Ceres spells it so that
// the fit's JSON and text report keep their content.
#include <gtest/gtest.h>

#include <sstream>

#include "tirpol/fitting/microfacet_fit.h"

namespace tirpol::fitting {
namespace {

TEST(SolverTermination, TextIsCeresSpellingThenTheMessage) {
    // ceres::TerminationTypeToString spells the types this way (ceres/types.cc).
    EXPECT_EQ(to_string(SolverTermination::Type::Convergence), "CONVERGENCE");
    EXPECT_EQ(to_string(SolverTermination::Type::NoConvergence), "NO_CONVERGENCE");
    EXPECT_EQ(to_string(SolverTermination::Type::Failure), "FAILURE");
    EXPECT_EQ(to_string(SolverTermination::Type::UserSuccess), "USER_SUCCESS");
    EXPECT_EQ(to_string(SolverTermination::Type::UserFailure), "USER_FAILURE");
    const SolverTermination t{SolverTermination::Type::NoConvergence,
                              "Maximum number of iterations reached."};
    EXPECT_EQ(t.text(), "NO_CONVERGENCE: Maximum number of iterations reached.");
    std::ostringstream streamed;
    streamed << t;
    EXPECT_EQ(streamed.str(), t.text());
    EXPECT_EQ(fmt::format("({})", t), "(" + t.text() + ")");
}

TEST(SolverTermination, NoSolveYetWritesNothing) {
    EXPECT_EQ(SolverTermination{}.type, SolverTermination::Type::NotRun);
    EXPECT_EQ(SolverTermination{}.text(), "");
}

}  // namespace
}  // namespace tirpol::fitting
