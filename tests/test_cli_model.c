/* CLI tests of the model commands (train, sample, bench-model; design.md §11):
 * --help exits 0, usage errors exit 2, bad or missing checkpoints exit 3 with
 * a message naming the file, and a training process killed with SIGKILL
 * resumes from its checkpoint to the same final bytes as an uninterrupted run. */
#include "testutil.h"
#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

static char out[65536];

static int run(const char *args) { return tu_run_cli("OPENBLAS_NUM_THREADS=1 ", args, out, sizeof out); }

static void test_model_commands_answer_help(void **s)
{
    (void)s;
    const char *c[] = {"train --help", "sample --help", "bench-model --help"};
    for (int i = 0; i < 3; i++) {
        if (run(c[i]) != 0) fail_msg("crownshy %s: exit != 0: %s", c[i], out);
        assert_non_null(strstr(out, "usage:"));
    }
}

static void test_usage_errors_exit_2(void **s)
{
    (void)s;
    assert_int_equal(run("train --bogus 3"), 2);
    assert_non_null(strstr(out, "--bogus"));
    assert_int_equal(run("train --steps ten"), 2);
    assert_non_null(strstr(out, "not an integer"));
    assert_int_equal(run("train --arm both"), 2);
    assert_int_equal(run("train --width 30 --heads 4"), 2); /* heads must divide width */
    assert_int_equal(run("train --steps"), 2);
    assert_int_equal(run("sample"), 2);
    assert_non_null(strstr(out, "--ckpt"));
    assert_int_equal(run("bench-model --repeats 0"), 2);
}

static void test_missing_and_tampered_checkpoints_exit_3(void **s)
{
    (void)s;
    const char *dir = tu_tmpdir("cli_model_bad");
    char a[1024], path[600];
    snprintf(path, sizeof path, "%s/none.ckpt", dir);
    snprintf(a, sizeof a, "sample --ckpt %s", path);
    assert_int_equal(run(a), 3);
    assert_non_null(strstr(out, path));
    snprintf(path, sizeof path, "%s/junk.ckpt", dir);
    tu_write(path, "CSHYCKPT but then nothing useful\n");
    snprintf(a, sizeof a, "sample --ckpt %s", path);
    assert_int_equal(run(a), 3);
    assert_non_null(strstr(out, "truncated"));
}

#define SMALL "train --width 32 --depth 2 --heads 2 --mlp 64 --batch 16 --stands 1 --steps 300 --ckpt-every 10"

static int file_equal(const char *a, const char *b)
{
    char cmd[1400];
    snprintf(cmd, sizeof cmd, "cmp -s '%s' '%s'", a, b);
    return system(cmd) == 0;
}

/* pair = 1: the pair-aware model (checkpoint format 2 with its z-scores) */
static void check_kill(int pair)
{
    const char *dir = tu_tmpdir(pair ? "cli_model_kill_pair" : "cli_model_kill");
    const char *extra = pair ? " --pair 1" : "";
    char straight[600], killed[600], a[2048];
    snprintf(straight, sizeof straight, "%s/straight.ckpt", dir);
    snprintf(killed, sizeof killed, "%s/killed.ckpt", dir);
    snprintf(a, sizeof a, SMALL "%s --ckpt %s", extra, straight);
    if (run(a) != 0) fail_msg("straight run failed: %s", out);
    assert_non_null(strstr(out, "final step 300"));

    pid_t pid = fork();
    assert_true(pid >= 0);
    if (pid == 0) {
        int fd = open("/dev/null", O_WRONLY);
        if (fd >= 0) { dup2(fd, 1); dup2(fd, 2); }
        setenv("OPENBLAS_NUM_THREADS", "1", 1);
        execl("build/crownshy", "crownshy", "train", "--width", "32", "--depth", "2", "--heads", "2",
              "--mlp", "64", "--batch", "16", "--stands", "1", "--steps", "300", "--ckpt-every", "10",
              "--pair", pair ? "1" : "0", "--ckpt", killed, (char *)NULL);
        _exit(127);
    }
    struct timespec ts = {0, 150 * 1000 * 1000};
    nanosleep(&ts, NULL);
    kill(pid, SIGKILL);
    int st;
    waitpid(pid, &st, 0);
    int was_killed = WIFSIGNALED(st);
    snprintf(a, sizeof a, SMALL "%s --ckpt %s", extra, killed);
    if (run(a) != 0) fail_msg("resumed run failed: %s", out);
    print_message("kill-and-resume%s: %s\n", extra,
                  was_killed ? (strstr(out, "resumed from") ? "killed mid-run, resumed"
                                                            : "killed before the first checkpoint, restarted")
                             : "finished before the kill");
    assert_true(file_equal(straight, killed));
}
static void test_killed_training_resumes_to_identical_bytes(void **s) { (void)s; check_kill(0); }
static void test_killed_pair_training_resumes_to_identical_bytes(void **s) { (void)s; check_kill(1); }

static void test_sample_runs_on_a_trained_checkpoint(void **s)
{
    (void)s;
    const char *dir = tu_tmpdir("cli_model_sample");
    char a[2048];
    snprintf(a, sizeof a,
             "train --width 16 --depth 1 --heads 2 --mlp 32 --batch 8 --stands 1 --steps 20 --ckpt %s/m.ckpt", dir);
    if (run(a) != 0) fail_msg("train failed: %s", out);
    snprintf(a, sizeof a, "sample --ckpt %s/m.ckpt --n 4 --euler 10", dir);
    if (run(a) != 0) fail_msg("sample failed: %s", out);
    assert_non_null(strstr(out, "clearance_generated_m"));
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_model_commands_answer_help),
        cmocka_unit_test(test_usage_errors_exit_2),
        cmocka_unit_test(test_missing_and_tampered_checkpoints_exit_3),
        cmocka_unit_test(test_killed_training_resumes_to_identical_bytes),
        cmocka_unit_test(test_killed_pair_training_resumes_to_identical_bytes),
        cmocka_unit_test(test_sample_runs_on_a_trained_checkpoint),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
