/* main of a demo binary that hosts one technique: the Makefile compiles
 * this once per demo with -DDEMO_TECHNIQUE=<name>_technique. */
#include "app.h"

extern const technique DEMO_TECHNIQUE;

int main(int argc, char **argv) {
    const technique *const techniques[] = {&DEMO_TECHNIQUE};
    return app_main(argc, argv, techniques, 1);
}
