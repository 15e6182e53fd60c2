// Compiled (not run) by ctest: dropping a hesai::Error must not compile. With no macro the file
// handles every error and compiles; each DROP_* macro drops one and must fail with "nodiscard".
#include "hesai/decoder.h"
#include "hesai/error.h"

namespace {

// A caller's own function: [[nodiscard]] on the type reaches it without an attribute of its own.
hesai::Error user_check(int v) { return v > 0 ? hesai::Error::ok : hesai::Error::invalid_argument; }

}  // namespace

int main() {
  hesai::Model model = hesai::Model::unknown;
  hesai::PacketKind kind = hesai::PacketKind::point_cloud;
#if defined(DROP_CORE_CALL)
  hesai::identify(hesai::ByteView{}, model, kind);
#elif defined(DROP_USER_FUNCTION)
  user_check(1);
#else
  if (hesai::identify(hesai::ByteView{}, model, kind) != hesai::Error::bad_length) return 1;
  if (user_check(1) != hesai::Error::ok) return 1;
#endif
  return 0;
}
