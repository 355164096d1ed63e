#pragma once
#include "tirpol/alpha/member.h"
namespace alpha {
struct Used {
    Member member;
};
}  // namespace alpha
