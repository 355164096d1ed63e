// The program tirpol-example-<name>: runs one example (examples.h); TIRPOL_EXAMPLE_NAME is set by
// examples/CMakeLists.txt.

#include "examples.h"

int main(int argc, char** argv) {
    return tirpol::examples::run_example_program(TIRPOL_EXAMPLE_NAME, argc, argv);
}
