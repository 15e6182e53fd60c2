// Compiles the header-only calibration tables with the core's flags (and, in the freestanding
// check, with -ffreestanding), so their static_asserts run in every core build.
#include "hesai/detail/tables/block_times.h"
#include "hesai/detail/tables/pandar40_tables.h"
#include "hesai/detail/tables/pandar64_tables.h"
#include "hesai/detail/tables/qt128_tables.h"
#include "hesai/detail/tables/qt64_tables.h"
#include "hesai/detail/tables/table_types.h"
#include "hesai/detail/tables/xt_tables.h"
