#ifdef __cplusplus
#pragma once
#include "cpp_prelude.h"
#endif
SHARED_BEGIN
const float PI = 3.14159265358979f;
const float INV_PI = 0.318309886183791f;
const float INV_2PI = 0.159154943091895f;
SHARED_END
