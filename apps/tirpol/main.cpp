#include "cli.h"

int main(int argc, char** argv) { return tirpol::cli::run(argc, argv); }
