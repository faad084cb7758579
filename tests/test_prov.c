/* Tests for src/base/sha256.c (FIPS 180-4 vectors) and src/base/prov.c. */
#include "testutil.h"
#include "sha256.h"
#include "prov.h"
#include "audit.h"
#include "teacher.h"

static void test_sha256_known_vectors(void **s)
{
    (void)s;
    char hex[65];
    sha256_hex("", 0, hex);
    assert_string_equal(hex, "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
    sha256_hex("abc", 3, hex);
    assert_string_equal(hex, "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
    const char *m = "abcdbcdecdefdefgefghfghighijhijkijkljklmklmnlmnomnopnopq";
    sha256_hex(m, strlen(m), hex);
    assert_string_equal(hex, "248d6a61d20638b8e5c026930c3e6039a33ce45964ff2167f6ecedd419db06c1");
}

static void test_sha256_streaming_equals_one_shot(void **s)
{
    (void)s;
    char big[1000];
    for (int i = 0; i < 1000; i++) big[i] = (char)(i * 7 + 3);
    char a[65], b[65];
    sha256_hex(big, sizeof big, a);
    sha256_ctx c;
    uint8_t d[32];
    sha256_init(&c);
    for (int i = 0; i < 1000; i += 37) sha256_update(&c, big + i, i + 37 <= 1000 ? 37 : 1000 - i);
    sha256_final(&c, d);
    sha256_tohex(d, b);
    assert_string_equal(a, b);
}

static void test_provenance_block_has_every_key(void **s)
{
    (void)s;
    const char *dir = tu_tmpdir("prov");
    char path[600];
    snprintf(path, sizeof path, "%s/p.tsv", dir);
    prov p;
    char *argv[] = {"run", "demo"};
    prov_begin(&p, "demo", 2, argv);
    snprintf(p.seeds, sizeof p.seeds, "seed_derive(demo,*,0..3,*)");
    p.worst_overlap_m = 0.0;
    tsv_writer *w;
    assert_int_equal(tsv_writer_open(&w, path), CS_OK);
    assert_int_equal(prov_write(w, &p), CS_OK);
    tsv_writer_columns(w, "x");
    tsv_writer_dbl(w, 1.5);
    tsv_writer_endrow(w);
    assert_int_equal(tsv_writer_commit(w), CS_OK);
    tsv *t;
    assert_int_equal(tsv_read(path, &t), CS_OK);
    const char *keys[] = {"experiment", "command", "teacher_version", "teacher_sha256", "estimator_sha256",
                          "gates_sha256", "git_commit", "seeds", "date", "wall_s", "worst_overlap_m"};
    for (size_t i = 0; i < sizeof keys / sizeof *keys; i++)
        if (!tsv_meta(t, keys[i])) fail_msg("missing provenance key %s", keys[i]);
    assert_string_equal(tsv_meta(t, "command"), "crownshy run demo");
    /* The default reading is the pinned one (audit/pins.tsv, read here). */
    tsv *pins;
    assert_int_equal(tsv_read(PATHS_PINS, &pins), CS_OK);
    long pr = tsv_find(pins, "key", "teacher_version");
    assert_true(pr >= 0);
    assert_string_equal(tsv_meta(t, "teacher_version"), tsv_str(pins, (size_t)pr, "value"));
    tsv_free(pins);
    assert_int_equal(strlen(tsv_meta(t, "gates_sha256")), 64);
    tsv_free(t);
}

static void test_gates_hash_changes_with_one_byte(void **s)
{
    (void)s;
    const char *dir = tu_tmpdir("prov_gates");
    char p1[600];
    snprintf(p1, sizeof p1, "%s/a.gate", dir);
    tu_write(p1, "x 0.20\n");
    char h1[65], h2[65];
    assert_int_equal(prov_gates_sha256(dir, h1), CS_OK);
    tu_write(p1, "x 0.19\n");
    assert_int_equal(prov_gates_sha256(dir, h2), CS_OK);
    assert_string_not_equal(h1, h2);
}

/* A result made by the one-sided reading says so in its provenance. */
static void test_provenance_names_the_teacher_reading(void **s)
{
    (void)s;
    const char *dir = tu_tmpdir("prov_reading");
    char path[600];
    snprintf(path, sizeof path, "%s/p.tsv", dir);
    teacher_params tp;
    teacher_params_default(&tp);
    tp.one_sided = 1;
    prov p;
    char *argv[] = {"run", "demo"};
    prov_begin(&p, "demo", 2, argv);
    snprintf(p.teacher_version, sizeof p.teacher_version, "%s", teacher_version(&tp));
    p.worst_overlap_m = 0.0;
    tsv_writer *w;
    assert_int_equal(tsv_writer_open(&w, path), CS_OK);
    assert_int_equal(prov_write(w, &p), CS_OK);
    tsv_writer_columns(w, "x");
    tsv_writer_dbl(w, 1.5);
    tsv_writer_endrow(w);
    assert_int_equal(tsv_writer_commit(w), CS_OK);
    tsv *t;
    assert_int_equal(tsv_read(path, &t), CS_OK);
    assert_string_equal(tsv_meta(t, "teacher_version"), "teacher-1");
    tsv_free(t);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_sha256_known_vectors),
        cmocka_unit_test(test_sha256_streaming_equals_one_shot),
        cmocka_unit_test(test_provenance_block_has_every_key),
        cmocka_unit_test(test_gates_hash_changes_with_one_byte),
        cmocka_unit_test(test_provenance_names_the_teacher_reading),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
