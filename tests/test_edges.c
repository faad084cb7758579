/* Behaviour at the edges (design.md §11): bad input never reaches
 * paper/, non-finite values are named, directories and byte-order marks are
 * clear input errors or handled, the field table loads in O(n log n),
 * concurrent atomic writers never share a temp file, a writer terminated
 * mid-write leaves none behind, the gate map and the
 * aggregate map parse strictly, per-tree tables name the claims they feed,
 * a file a frozen record names is found where it lies now.
 * CLI cases run build/crownshy in a scratch copy (build/test-tmp/edges_*). */
#include "testutil.h"
#include "afile.h"
#include "audit_data.h"
#include "claims.h"
#include "field.h"
#include "paths.h"
#include <fcntl.h>
#include <signal.h>
#include <sys/file.h>
#include <sys/wait.h>
#include <unistd.h>

static char out[65536];

/* A scratch copy of the repository's inputs with build/crownshy linked in. */
static const char *scratch(const char *name)
{
    const char *dir = tu_tmpdir(name);
    char cmd[2048];
    snprintf(cmd, sizeof cmd,
             "tar cf - src gates frozen audit paper figures | (cd '%s' && tar xf -) && mkdir -p '%s/build' && ln -s "
             "\"$PWD/build/crownshy\" '%s/build/crownshy'",
             dir, dir, dir);
    if (system(cmd) != 0) fail_msg("cannot copy the repository into %s", dir);
    return dir;
}

static int run_in(const char *dir, const char *env, const char *args)
{
    char pre[2600];
    snprintf(pre, sizeof pre, "cd '%s' && env -u FIELD_TABLE -u CHM %s ", dir, env);
    return tu_run_cli(pre, args, out, sizeof out);
}

/* paper/ of the scratch copy is byte-identical to the repository's, and holds no temp file */
static void assert_paper_untouched(const char *dir)
{
    char cmd[1200];
    snprintf(cmd, sizeof cmd, "diff -r paper '%s/paper' >/dev/null", dir);
    if (system(cmd) != 0) fail_msg("%s/paper differs from paper/ after a command with bad input", dir);
}

static void test_numbers_bad_field_table_writes_nothing(void **s)
{
    (void)s;
    const char *dir = scratch("edges_numbers_field");
    char env[1200], p[1100];
    tu_write_in(p, sizeof p, dir, "bad.tsv", "tree\tdirection\tclearance_m\nx\tE\tabc\n");
    snprintf(env, sizeof env, "FIELD_TABLE=bad.tsv");
    assert_int_equal(run_in(dir, env, "numbers"), 3);
    assert_non_null(strstr(out, "bad.tsv:2: field 'clearance_m'"));
    assert_non_null(strstr(out, "nothing written"));
    assert_paper_untouched(dir);
}

static void test_numbers_chm_1e300_never_writes_inf(void **s)
{
    (void)s;
    const char *dir = scratch("edges_numbers_chm");
    char p[1100];
    tu_write_in(p, sizeof p, dir, "chm.asc",
                "ncols 1e300\nnrows 1e300\nxllcorner 0\nyllcorner 0\ncellsize 1e300\nNODATA_value -9999\n1 2\n");
    assert_int_equal(run_in(dir, "CHM=chm.asc", "numbers"), 3);
    assert_non_null(strstr(out, "RealChmSpan"));
    assert_non_null(strstr(out, "field 'ncols'"));
    assert_paper_untouched(dir);
    /* a directory given as the CHM is an input error too, and writes nothing */
    assert_int_equal(run_in(dir, "CHM=frozen", "numbers"), 3);
    assert_paper_untouched(dir);
}

/* The CHM reader validates every header field and the value count: each bad
 * grid is exit 3 naming its field, and nothing reaches paper/. */
static void test_chm_header_and_values_validated(void **s)
{
    (void)s;
    const char *dir = scratch("edges_chm_fields");
    char p[1100];
    snprintf(p, sizeof p, "%s/chm.asc", dir);
    const char *hdr = "ncols 2\nnrows 2\nxllcorner 0\nyllcorner 0\ncellsize 0.5\nNODATA_value -9999\n";
    const char *bad[][2] = {
        {"", "field 'nrows': 0 data rows"},                       /* a header with no data rows */
        {"1 2\n3\n", "field 'ncols': 1 values on the row"},      /* a short row */
        {"1 2\n3 4\n5 6\n", "more data rows than nrows"},
        {"1 2\n3 x\n", "field 'column 2': 'x'"},
        {"1 2\n3 nan\n", "field 'column 2': 'nan'"},
    };
    for (size_t i = 0; i < sizeof bad / sizeof *bad; i++) {
        char text[512];
        snprintf(text, sizeof text, "%s%s", hdr, bad[i][0]);
        tu_write(p, text);
        assert_int_equal(run_in(dir, "CHM=chm.asc", "numbers"), 3);
        if (!strstr(out, bad[i][1])) fail_msg("case %zu: output lacks '%s': %s", i, bad[i][1], out);
        assert_paper_untouched(dir);
    }
    const char *hbad[][2] = {
        {"ncols nan\nnrows 2\nxllcorner 0\nyllcorner 0\ncellsize 1\n1 2\n3 4\n", "field 'ncols': 'nan' is not one finite number"},
        {"ncols 2.5\nnrows 2\nxllcorner 0\nyllcorner 0\ncellsize 1\n1 2\n3 4\n", "field 'ncols': 2.5 is not a whole number"},
        {"ncols 2\nnrows 2\nxllcorner 0\nyllcorner 0\ncellsize -1\n1 2\n3 4\n", "field 'cellsize'"},
        {"ncols 2\nnrows 2\nyllcorner 0\ncellsize 1\n1 2\n3 4\n", "field 'xllcorner': missing"},
        {"ncols 2\nncols 2\nnrows 2\nxllcorner 0\nyllcorner 0\ncellsize 1\n1 2\n3 4\n", "field 'ncols': given twice"},
        {"ncols 2\nnrows 2\nxllcorner 0\nyllcorner 0\ncellsize 1\nbogus 3\n1 2\n3 4\n", "field 'bogus'"},
    };
    for (size_t i = 0; i < sizeof hbad / sizeof *hbad; i++) {
        tu_write(p, hbad[i][0]);
        assert_int_equal(run_in(dir, "CHM=chm.asc", "numbers"), 3);
        if (!strstr(out, hbad[i][1])) fail_msg("header case %zu: output lacks '%s': %s", i, hbad[i][1], out);
    }
    assert_int_equal(run_in(dir, "CHM=frozen", "numbers"), 3);
    assert_non_null(strstr(out, "frozen: is a directory"));
    assert_null(strstr(out, "header incomplete"));
    /* a good grid is computed: 2 x 2 cells of 0.5 m */
    snprintf(p, sizeof p, "%s/good.asc", dir);
    char text[512];
    snprintf(text, sizeof text, "%s1 2\n3 4\n", hdr);
    tu_write(p, text);
    assert_int_equal(run_in(dir, "CHM=good.asc", "trace RealChmSpan"), 0);
    assert_non_null(strstr(out, "value        1"));
}

/* Errors by kind (design.md §11), from crownshy and through make: an
 * inconsistency 1, a bad FIELD_TABLE 3 (not "INCONSISTENT"), a build/ that
 * cannot be written 4; make names crownshy's status and its kind. */
static void test_exit_codes_by_kind(void **s)
{
    (void)s;
    const char *dir = scratch("edges_exit");
    char cmd[3000], root[1024];
    assert_non_null(getcwd(root, sizeof root));
    snprintf(cmd, sizeof cmd, "cp Makefile '%s/' && printf 'tree\tdirection\tclearance_m\nx\tE\tabc\n' > '%s/bad.tsv'",
             dir, dir);
    assert_int_equal(system(cmd), 0);
    assert_int_equal(run_in(dir, "FIELD_TABLE=bad.tsv", "verify --no-figures"), 3);
    assert_non_null(strstr(out, "bad.tsv:2: field 'clearance_m'"));
    assert_null(strstr(out, "INCONSISTENT"));
    /* through make: GNU make exits 2; the recipe names crownshy's status */
    char mk[1200];
    snprintf(mk, sizeof mk, "make -s --no-print-directory verify B='%s/build'", root);
    snprintf(cmd, sizeof cmd, "cd '%s' && env -u FIELD_TABLE -u CHM -u MAKEFLAGS -u MAKELEVEL", dir);
    char args[1400];
    snprintf(args, sizeof args,
             "--help >/dev/null; make -s --no-print-directory numbers FIELD_TABLE=bad.tsv B='%s/build'", root);
    assert_int_not_equal(tu_run_cli(cmd, args, out, sizeof out), 0);
    assert_non_null(strstr(out, "crownshy exited 3 (bad input)"));
    snprintf(cmd, sizeof cmd,
             "cd '%s' && sed -i 's/^\\newcommand{\\MechRows}{16}/\\newcommand{\\MechRows}{17}/' paper/numbers.tex && "
             "env -u FIELD_TABLE -u CHM -u MAKEFLAGS -u MAKELEVEL %s > make.log 2>&1; echo $? >> make.log",
             dir, mk);
    if (system(cmd) != 0) { /* the status is in make.log */ }
    char p[1100], log[8192] = "";
    snprintf(p, sizeof p, "%s/make.log", dir);
    FILE *f = fopen(p, "r");
    assert_non_null(f);
    fseek(f, 0, SEEK_END);
    long size = ftell(f);
    fseek(f, size > (long)sizeof log - 1 ? size - (long)sizeof log + 1 : 0,
          SEEK_SET); /* the end: summary, make's lines */
    size_t n = fread(log, 1, sizeof log - 1, f);
    log[n] = '\0';
    fclose(f);
    if (!strstr(log, "crownshy exited 1 (inconsistency)"))
        fail_msg("make verify does not name the inconsistency: %s", log + (n > 600 ? n - 600 : 0));
    assert_non_null(strstr(log, "Error 1"));
    /* a build/ that cannot be written (mkdir is refused in /sys, also to root) */
    snprintf(cmd, sizeof cmd,
             "cd '%s' && rm -rf build && ln -s /sys build && env -u FIELD_TABLE -u CHM '%s/build/crownshy' verify "
             "--no-figures > out.log 2>&1; echo \"rc=$?\" >> out.log",
             dir, root);
    if (system(cmd) != 0) { /* the status is in out.log */ }
    snprintf(p, sizeof p, "%s/out.log", dir);
    f = fopen(p, "r");
    assert_non_null(f);
    n = fread(log, 1, sizeof log - 1, f);
    log[n] = '\0';
    fclose(f);
    if (!strstr(log, "rc=4") || !strstr(log, "build/: cannot create"))
        fail_msg("a read-only build/ is not an environment error: %s", log);
    assert_null(strstr(log, "INCONSISTENT"));
}

/* One make reproduce per tree: while the lock is held a second refuses
 * clearly (and never starts); released, the next one runs. */
static void test_reproduce_lock(void **s)
{
    (void)s;
    const char *dir = tu_tmpdir("edges_lock");
    char cmd[3000], root[1024], p[1100];
    assert_non_null(getcwd(root, sizeof root));
    snprintf(cmd, sizeof cmd, "cp Makefile '%s/' && tar cf - src | (cd '%s' && tar xf -) && mkdir -p '%s/build'", dir,
             dir, dir);
    assert_int_equal(system(cmd), 0);
    snprintf(p, sizeof p, "%s/build/reproduce.lock", dir);
    int fd = open(p, O_WRONLY | O_CREAT, 0666);
    assert_true(fd >= 0);
    assert_int_equal(flock(fd, LOCK_EX | LOCK_NB), 0);
    snprintf(cmd, sizeof cmd, "cd '%s' && env -u MAKEFLAGS -u MAKELEVEL", dir);
    char args[1400];
    snprintf(args, sizeof args, "--help >/dev/null; make -s --no-print-directory reproduce ENGINE=none B='%s/build'",
             root);
    assert_int_not_equal(tu_run_cli(cmd, args, out, sizeof out), 0);
    assert_non_null(strstr(out, "another make reproduce is running in this tree"));
    assert_null(strstr(out, "unknown ENGINE"));
    flock(fd, LOCK_UN);
    close(fd);
    /* released: the run starts (and stops at the engine name, before any unit) */
    assert_int_not_equal(tu_run_cli(cmd, args, out, sizeof out), 0);
    assert_null(strstr(out, "another make reproduce"));
    assert_non_null(strstr(out, "unknown ENGINE or mode 'none'"));
}

static void test_directory_as_input_is_input_error(void **s)
{
    (void)s;
    assert_int_equal(tu_run_cli("env -u FIELD_TABLE ", "field-summary frozen", out, sizeof out), 3);
    assert_non_null(strstr(out, "frozen: is a directory"));
    assert_null(strstr(out, "out of memory"));
    assert_int_equal(tu_run_cli("", "check-tsv frozen/extension-pair-16-stands/main", out, sizeof out), 3);
    assert_non_null(strstr(out, "is a directory"));
    assert_int_equal(tu_run_cli("", "gates frozen", out, sizeof out), 3);
    assert_non_null(strstr(out, "is a directory"));
    assert_int_equal(tu_run_cli("", "sample --ckpt frozen", out, sizeof out), 3);
    assert_non_null(strstr(out, "frozen: is a directory"));
    assert_null(strstr(out, "out of memory"));
}

/* field-summary of a table holding text, with no FIELD_TABLE from the caller's environment. */
static int field_summary_of(const char *scratch, const char *file, const char *text)
{
    return tu_run_cli_on("env -u FIELD_TABLE ", "field-summary", scratch, file, text, out, sizeof out);
}

static void test_utf8_bom_is_handled(void **s)
{
    (void)s;
    assert_int_equal(field_summary_of("edges_bom", "bom.tsv",
                                      "\xef\xbb\xbftree\tdirection\tclearance_m\nx\tE\t0.5\nx\tN\t0.5\n"
                                      "x\tW\t0.5\nx\tS\t0.5\n"),
                     0);
    assert_non_null(strstr(out, "trees\t1"));
}

static void test_huge_value_names_file_line_field(void **s)
{
    (void)s;
    assert_int_equal(field_summary_of("edges_huge", "huge.tsv",
                                      "tree\tdirection\tclearance_m\nx\tE\t0.5\nx\tN\t1e308\nx\tW\t0.5\nx\tS\t0.5\n"),
                     3);
    assert_non_null(strstr(out, "huge.tsv:3: field 'clearance_m'"));
}

/* 10^6 rows load correctly (the quadratic loader took minutes on them; the
 * O(n log n) one, 0.45 s here, is timed by hand, never by a test: design.md §10). */
static void test_field_table_million_rows_loads(void **s)
{
    (void)s;
    char p[600];
    snprintf(p, sizeof p, "%s/big.tsv", tu_tmpdir("edges_big"));
    FILE *f = fopen(p, "w");
    assert_non_null(f);
    fputs("tree\tdirection\tclearance_m\n", f);
    const char *dirs = "ENWS";
    for (int d = 0; d < 4; d++)       /* directions interleaved across the file */
        for (int i = 0; i < 250000; i++) fprintf(f, "t%06d\t%c\t%d.25\n", (i * 7919) % 250000, dirs[d], i % 3);
    fclose(f);
    field_table ft;
    assert_int_equal(field_table_load(p, &ft), CS_OK);
    assert_int_equal(ft.n, 250000);
    /* trees in order of first appearance, each with its four directions */
    assert_string_equal(ft.id[0], "t000000");
    assert_string_equal(ft.id[1], "t007919");
    for (size_t i = 0; i < ft.n; i++)
        for (int c = 0; c < 4; c++) if (!isfinite(ft.gap[i][c])) fail_msg("tree %s lacks direction %d", ft.id[i], c);
    field_table_free(&ft);
}

static void test_field_table_duplicate_still_named(void **s)
{
    (void)s;
    char p[600];
    tu_write_in(p, sizeof p, tu_tmpdir("edges_dup"), "dup.tsv",
                "tree\tdirection\tclearance_m\nb\tE\t1\na\tE\t1\nb\tE\t2\n");
    field_table ft;
    assert_int_equal(field_table_load(p, &ft), CS_EINPUT);
    assert_non_null(strstr(cs_errmsg(), "dup.tsv:4: field 'direction': tree 'b' already has direction E (line 2)"));
}

static void test_concurrent_atomic_writers_do_not_collide(void **s)
{
    (void)s;
    char p[600];
    snprintf(p, sizeof p, "%s/x.txt", tu_tmpdir("edges_afile"));
    afile a, b;
    assert_int_equal(afile_open(&a, p), CS_OK);
    assert_int_equal(afile_open(&b, p), CS_OK);
    assert_string_not_equal(a.tmp, b.tmp);
    fputs("first\n", a.f);
    fputs("second\n", b.f);
    assert_int_equal(afile_commit(&a), CS_OK);
    assert_int_equal(afile_commit(&b), CS_OK);
    FILE *f = fopen(p, "r");
    char line[64] = "";
    assert_non_null(f);
    assert_non_null(fgets(line, sizeof line, f));
    fclose(f);
    assert_string_equal(line, "second\n");
}

/* A writer terminated between open and commit (SIGTERM: what scancel, a
 * batch system's time limit or kill send) removes its live temp files and
 * still dies of that signal, so make and Slurm see the unit as failed; a file
 * it committed before stays. Two live files, so one registration cannot pass. */
static void test_terminated_writer_leaves_no_temp_file(void **s)
{
    (void)s;
    const char *dir = tu_tmpdir("edges_term");
    char done[600], p1[600], p2[600];
    snprintf(done, sizeof done, "%s/done.tsv", dir);
    snprintf(p1, sizeof p1, "%s/run_s01_joint.tsv", dir);
    snprintf(p2, sizeof p2, "%s/samples_s01_joint.tsv", dir);
    int ready[2];
    assert_int_equal(pipe(ready), 0);
    pid_t pid = fork();
    assert_true(pid >= 0);
    if (pid == 0) {
        close(ready[0]);
        afile_remove_on_signal();
        afile d, a, b;
        if (afile_open(&d, done) != CS_OK) _exit(90);
        fputs("committed\n", d.f);
        if (afile_commit(&d) != CS_OK) _exit(91);
        if (afile_open(&a, p1) != CS_OK || afile_open(&b, p2) != CS_OK) _exit(92);
        fputs("half a unit\n", a.f);
        fputs("half its samples\n", b.f);
        fflush(a.f);
        fflush(b.f);
        if (write(ready[1], "r", 1) != 1) _exit(93);
        for (;;) pause();
    }
    close(ready[1]);
    char c;
    if (read(ready[0], &c, 1) != 1) fail_msg("the writer exited before it was ready");
    close(ready[0]);
    assert_int_equal(kill(pid, SIGTERM), 0);
    int st = 0;
    assert_int_equal(waitpid(pid, &st, 0), pid);
    if (!WIFSIGNALED(st) || WTERMSIG(st) != SIGTERM)
        fail_msg("the writer did not die of SIGTERM (status %#x)", st);
    char cmd[800];
    snprintf(cmd, sizeof cmd, "cd '%s' && test \"$(ls -A)\" = done.tsv", dir);
    if (system(cmd) != 0) {
        snprintf(cmd, sizeof cmd, "ls -A '%s' >&2", dir);
        if (system(cmd) != 0) {}
        fail_msg("%s: expected only done.tsv after SIGTERM (listing above)", dir);
    }
}

static void test_gate_map_parses_strictly(void **s)
{
    (void)s;
    const char *dir = tu_tmpdir("edges_gatemap");
    char p[600];
    snprintf(p, sizeof p, "%s/map.tsv", dir);
    claims c;
    assert_int_equal(claims_registry(&c), CS_OK);
    const char *bad[][2] = {{"macro\tgate\nNoSuchClaim\tmain.gate:seeds\n", "map.tsv:2: field 'macro'"},
                            {"macro\tgate\nMainRel\tmain.gate:seeds\nMainRel\tmain.gate:seeds\n", "map.tsv:3: field 'macro'"},
                            {"macro\tgate\nMainRel\tmain:seeds\n", "map.tsv:2: field 'gate'"},
                            {"macro\tgate\nMainRel\t-\n", "map.tsv:2: field 'gate'"},
                            {"name\tgate\nMainRel\tmain.gate:x\n", "'macro' and 'gate'"}};
    for (size_t i = 0; i < sizeof bad / sizeof *bad; i++) {
        tu_write(p, bad[i][0]);
        assert_int_equal(claims_apply_gate_map(&c, p), CS_EINPUT);
        if (!strstr(cs_errmsg(), bad[i][1])) fail_msg("case %zu: '%s' lacks '%s'", i, cs_errmsg(), bad[i][1]);
    }
    /* the map decides: a claim it does not name has no gate */
    tu_write(p, "macro\tgate\nMainRel\tmain.gate:rel_improvement_min\n");
    assert_int_equal(claims_apply_gate_map(&c, p), CS_OK);
    assert_string_equal(claims_find(&c, "MainRel")->gate, "main.gate:rel_improvement_min");
    assert_string_equal(claims_find(&c, "MainGeomRatio")->gate, "-");
    assert_string_equal(claims_find(&c, "MainGeomRatio")->gate_reg, "main.gate:shuffle_ratio_min");
    claims_free(&c);
}

static void test_aggregate_map_parses_strictly(void **s)
{
    (void)s;
    char p[600];
    snprintf(p, sizeof p, "%s/agg.tsv", tu_tmpdir("edges_agg"));
    const char *hdr = "aggregate\tvalue\treduce\tparts\tpart_value\tfilter\n";
    const char *bad[][2] = {{"frozen/a.tsv\tx\tmedian\tfrozen/b.tsv\ty\t-\n", "field 'reduce'"},
                            {"frozen/a.tsv\tx\tmean\tfrozen/b_{s.tsv\ty\t-\n", "field 'parts'"},
                            {"frozen/a.tsv\tx\tmean\tfrozen/b_{s:2}.tsv\ty\t-\n", "field 'parts'"},
                            {"/etc/a.tsv\tx\tmean\tfrozen/b.tsv\ty\t-\n", "under frozen/"},
                            {"frozen/a.tsv\tx\tmean\tfrozen/b.tsv\t-\t-\n", "needs a part_value"},
                            {"frozen/a.tsv\tx\tmean\tfrozen/b.tsv\ty\tnoequals\n", "field 'filter'"}};
    for (size_t i = 0; i < sizeof bad / sizeof *bad; i++) {
        char text[512];
        snprintf(text, sizeof text, "%s%s", hdr, bad[i][0]);
        tu_write(p, text);
        aggr_spec *a;
        size_t n;
        assert_int_equal(aggr_load(p, &a, &n), CS_EINPUT);
        if (!strstr(cs_errmsg(), bad[i][1])) fail_msg("case %zu: '%s' lacks '%s'", i, cs_errmsg(), bad[i][1]);
    }
}

static void test_per_tree_tables_name_their_claims(void **s)
{
    (void)s;
    claims c;
    assert_int_equal(claims_registry(&c), CS_OK);
    char buf[600];
    audit_feeds(&c, "frozen/field/heldout_trees.tsv", buf, sizeof buf);
    assert_non_null(strstr(buf, "Elong"));
    assert_non_null(strstr(buf, "via frozen/field/heldout.tsv"));
    audit_feeds(&c, "frozen/extension-pair-16-stands/main/run_s03_indep.tsv", buf, sizeof buf);
    assert_non_null(strstr(buf, "MainRel"));
    audit_feeds(&c, "frozen/readings/one-sided-60m/field/heldout_trees.tsv", buf, sizeof buf);
    assert_non_null(strstr(buf, "readings"));
    claims_free(&c);
}

/* A file a frozen record names by the place it was frozen at is followed to
 * where it lies now (paths.h); any other named file is left as named. */
static void test_recorded_paths_follow_their_folder(void **s)
{
    (void)s;
    char p[512];
    assert_int_equal(paths_recorded("frozen/generator-probes/pair/../../main/weights_s01_joint.ckpt", p, sizeof p), 1);
    assert_string_equal(p, "frozen/extension-pair-16-stands/main/weights_s01_joint.ckpt");
    assert_int_equal(access(p, F_OK), 0);
    assert_int_equal(paths_recorded("frozen/extrapolation/runs.tsv", p, sizeof p), 1);
    assert_string_equal(p, "frozen/extension-pair-16-stands/extrapolation/runs.tsv");
    assert_int_equal(
        paths_recorded("frozen/generator-probes/plain/../../model-readings/plain/main/weights_s01_joint.ckpt", p,
                       sizeof p),
        0);
    assert_string_equal(p, "frozen/generator-probes/plain/../../model-readings/plain/main/weights_s01_joint.ckpt");
    assert_int_equal(paths_recorded("frozen/paper-reading/main/./runs.tsv", p, sizeof p), 0);
    assert_string_equal(p, "frozen/paper-reading/main/./runs.tsv");
}

static void test_verify_documents_exit_codes(void **s)
{
    (void)s;
    assert_int_equal(tu_run_cli("", "verify --help", out, sizeof out), 0);
    assert_non_null(strstr(out, "--strict"));
    for (int k = 0; k <= 4; k++) {
        char code[8];
        snprintf(code, sizeof code, "%d:", k);
        if (!strstr(out, code)) fail_msg("verify --help does not document exit %d", k);
    }
    assert_int_equal(tu_run_cli("", "verify --bogus", out, sizeof out), 2);
}

/* make deps-paper runs src/cli/paper_deps.sh, which updates apt's lists
 * before it installs (a fresh machine has none) */
static void test_deps_paper_updates_apt_first(void **s)
{
    (void)s;
    FILE *f = fopen("src/cli/paper_deps.sh", "r");
    assert_non_null(f);
    char line[1024];
    int update = 0, install = 0;
    while (fgets(line, sizeof line, f)) {
        if (line[0] == '#' || strstr(line, "echo")) continue;
        if (strstr(line, "apt-get update") && !install) update = 1;
        if (strstr(line, "apt-get install")) install = 1;
    }
    fclose(f);
    assert_true(install);
    assert_true(update);
}

/* A write past the file-size limit (ulimit -f) is an environment failure:
 * exit 4 naming the file, and no temporary file left behind (the signal the
 * kernel sends for it would otherwise kill the command silently). */
static void test_file_size_limit_is_an_environment_error(void **s)
{
    (void)s;
    const char *dir = tu_tmpdir("edges_fsize");
    char args[1400];
    snprintf(args, sizeof args, "generator-probes-run --perfect --samples %s/samples.tsv --out %s/probes.tsv", dir,
             dir);
    int rc = tu_run_cli("ulimit -f 16; ", args, out, sizeof out);
    if (rc != 4) fail_msg("exit %d under ulimit -f, expected 4 (environment): %s", rc, out);
    assert_non_null(strstr(out, "samples.tsv"));
    char cmd[800];
    snprintf(cmd, sizeof cmd, "test -z \"$(ls '%s')\"", dir);
    if (system(cmd) != 0) fail_msg("%s: files left behind after the failed write", dir);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_numbers_bad_field_table_writes_nothing),
        cmocka_unit_test(test_numbers_chm_1e300_never_writes_inf),
        cmocka_unit_test(test_chm_header_and_values_validated),
        cmocka_unit_test(test_exit_codes_by_kind),
        cmocka_unit_test(test_reproduce_lock),
        cmocka_unit_test(test_directory_as_input_is_input_error),
        cmocka_unit_test(test_utf8_bom_is_handled),
        cmocka_unit_test(test_huge_value_names_file_line_field),
        cmocka_unit_test(test_field_table_million_rows_loads),
        cmocka_unit_test(test_field_table_duplicate_still_named),
        cmocka_unit_test(test_concurrent_atomic_writers_do_not_collide),
        cmocka_unit_test(test_terminated_writer_leaves_no_temp_file),
        cmocka_unit_test(test_gate_map_parses_strictly),
        cmocka_unit_test(test_aggregate_map_parses_strictly),
        cmocka_unit_test(test_per_tree_tables_name_their_claims),
        cmocka_unit_test(test_recorded_paths_follow_their_folder),
        cmocka_unit_test(test_verify_documents_exit_codes),
        cmocka_unit_test(test_deps_paper_updates_apt_first),
        cmocka_unit_test(test_file_size_limit_is_an_environment_error),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
