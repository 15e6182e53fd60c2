// The smallest and most portable configuration of the core (hesai/config.h), reached through
// HESAI_CONFIG_HEADER by tests/CMakeLists.txt (hesai_core_minimal, ctest minimal.*): the 1 KiB CRC
// table, no signature code, the ISO C++ path of every GNU extension, and the contract checks
// armed. The program defines hesai_test_contract_broken().
#pragma once

#define HESAI_CRC_SLICING 1
#define HESAI_SIGNATURE 0
#define HESAI_NO_GNU_EXTENSIONS

void hesai_test_contract_broken(const char* condition) noexcept;
#define HESAI_ASSERT(x) ((x) ? (void)0 : hesai_test_contract_broken(#x))
