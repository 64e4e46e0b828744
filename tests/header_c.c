/* header_c.c - pw85.h compiles as strict C99 (-std=c99 -pedantic -Wall
 * -Wextra -Werror, see tests/meson.build) and its declarations link. */
#include <pw85.h>
#include <stdio.h>
#include <string.h>

int main(void) {
  /* The loaded library is the one the header describes. */
  if (strcmp(pw85_version(), PW85_VERSION) != 0) {
    printf("pw85_version() = %s, PW85_VERSION = %s\n", pw85_version(), PW85_VERSION);
    return 1;
  }
  printf("ok - pw85.h as C99: pw85_version() = %s\n", pw85_version());
  return 0;
}
