#include <lagfsi/app.hpp>

namespace lagfsi {
int app_main(int, char**) { return 0; }
}  // namespace lagfsi
