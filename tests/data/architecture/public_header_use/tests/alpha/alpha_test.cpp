#include "tirpol/alpha/own_only.h"
