#include "tirpol/alpha/own_only.h"
#include "tirpol/alpha/used.h"
