// Compiles the header-only calibration tables with the core's flags (and, in the freestanding
// check, with -ffreestanding), so their static_asserts run in every core build.
#include "hesai/tables/block_times.h"
#include "hesai/tables/pandar40_tables.h"
#include "hesai/tables/pandar64_tables.h"
#include "hesai/tables/qt128_tables.h"
#include "hesai/tables/qt64_tables.h"
#include "hesai/tables/table_types.h"
#include "hesai/tables/xt_tables.h"
