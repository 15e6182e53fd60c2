// A program outside the project that links the installed hesai::core.
#include <cstdio>

#include "hesai/crc32.h"
#include "hesai/error.h"

int main() {
  const unsigned char check[] = {'1', '2', '3', '4', '5', '6', '7', '8', '9'};
  const unsigned crc = hesai::crc32_mpeg2(hesai::ByteView{check, sizeof check});
  std::printf("crc32_mpeg2(\"123456789\") = 0x%08X, %s\n", crc, hesai::error_name(hesai::Error::crc_body));
  return crc == 0x0376E6E7u ? 0 : 1;
}
