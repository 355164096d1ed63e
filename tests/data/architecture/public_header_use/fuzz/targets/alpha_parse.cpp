#include "tirpol/alpha/bench_only.h"
