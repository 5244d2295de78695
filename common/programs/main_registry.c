/* main of build/shadows: every registered technique in one program. */
#include "app.h"
#include "registry.h"

int main(int argc, char **argv) {
    return app_main(argc, argv, registry_techniques, registry_technique_count, NULL, 0);
}
