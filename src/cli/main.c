/* main: the crownshy executable; everything else of the CLI is in the cli
 * library (cli.h), so the tests can call the command handlers directly. */
#include "cli.h"

int main(int argc, char **argv) { return cli_main(argc, argv); }
