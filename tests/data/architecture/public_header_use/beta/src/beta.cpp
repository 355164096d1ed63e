#include "tirpol/alpha/used.h"
