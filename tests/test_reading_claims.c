/* Tests for the claims of a generator reading (design.md §8, §9;
 * src/claims/mainruns.c, claim_main.c, claim_comp.c, the two gate maps):
 * a reading's per-run tables gathered into its claims, pending while any unit
 * of the design is missing (naming how many seeds are frozen and which units
 * are not), and, with a fabricated 12-seed fixture written here (never under
 * frozen/), the gated values and verdicts, equal bit for bit to the same
 * claims computed from main-summary's runs.tsv; the extension map judging
 * extension rows only; E7 medians and ranges from a comparison-dist summary. */
#include "testutil.h"
#include "claims.h"
#include "interval.h"
#include "mainruns.h"
#include "mainsum.h"
#include "paths.h"
#include "stats.h"
#include <unistd.h>

/* The fixture's W1: joint near the paper reading's level, independent above,
 * the shuffled joint arm barely worse (a ratio below the gate's 1.30). */
static double w1_of(int seed, int indep, int probe, double d)
{
    double base = indep ? 0.78 + 0.004 * seed : 0.40 + 0.003 * seed;
    double sp = 0.02 * (d - 5.0) + 0.001 * (seed % 3);
    double mul = probe == 0 ? 1.0 : probe == 1 ? 1.02 + 0.001 * seed : 2.0;
    return (base + sp) * mul;
}

/* One unit's run table: unseen 4, 5, 6 m x 3 probes, extrap 3.0 and 7.5 m generated. */
static void write_unit(const char *dir, int seed, int indep)
{
    char p[1400], buf[4096];
    static const char *probe[3] = {"generated", "shuffled", "rotated"};
    snprintf(p, sizeof p, "%s/run_s%02d_%s.tsv", dir, seed, indep ? "indep" : "joint");
    size_t o = (size_t)snprintf(
        buf, sizeof buf,
        "# model: T 24 P 24 width 64 blocks 3 heads 4 mlp 256 joint %d pair 0 params 159000 reading paper\n"
        "# train_time: train_s 1900 steps_per_s %g (this "
        "invocation)\nseed\tarm\tspacing\tsplit\tprobe\tw1\tn_gen\tn_teacher\n",
        !indep, 7.0 + seed + 0.5 * indep);
    for (int k = 0; k < 3; k++)
        for (int q = 0; q < 3; q++)
            o += (size_t)snprintf(buf + o, sizeof buf - o, "%d\t%s\t%d\tunseen\t%s\t%.17g\t1536\t6145\n", seed,
                                  indep ? "indep" : "joint", 4 + k, probe[q], w1_of(seed, indep, q, 4 + k));
    const double ex[2] = {3.0, 7.5};
    for (int k = 0; k < 2; k++)
        o += (size_t)snprintf(buf + o, sizeof buf - o, "%d\t%s\t%g\textrap\tgenerated\t%.17g\t1536\t6128\n", seed,
                              indep ? "indep" : "joint", ex[k], w1_of(seed, indep, 0, ex[k]) * (k ? 1.3 : 0.8));
    tu_write(p, buf);
}

/* root/paper-reading/main/ with seeds 1..nseeds and the baselines. */
static const char *fixture(const char *name, int nseeds)
{
    static char dir[600];
    const char *root = tu_tmpdir(name);
    snprintf(dir, sizeof dir, "%s/paper-reading/main", root);
    char cmd[1400];
    snprintf(cmd, sizeof cmd, "mkdir -p '%s' '%s/paper-reading/extrapolation'", dir, root);
    assert_int_equal(system(cmd), 0);
    for (int s = 1; s <= nseeds; s++) { write_unit(dir, s, 0); write_unit(dir, s, 1); }
    char p[1400];
    snprintf(p, sizeof p, "%s/baselines.tsv", dir);
    tu_write(p, "spacing\tsplit\tdirection_blind_w1\tnoise_floor_w1\tteacher_shuffled_w1\tteacher_rotated_w1\tn_"
                "teacher\tn_half\n"
                "4\tunseen\t0.6\t0.002\t0.36\t0.81\t6145\t3069\n5\tunseen\t0.8\t0.0017\t0.42\t1.04\t6155\t3071\n"
                "6\tunseen\t0.95\t0.0018\t0.48\t1.21\t6137\t3069\n3\textrap\t0.47\t0.001\t0.29\t0.61\t6128\t3056\n"
                "7.5\textrap\t0.86\t0.005\t0.6\t1.03\t6127\t3068\n");
    return dir;
}

/* A fixture row computes what the registry's row of that claim computes:
 * its params (none for a name the registry lacks). */
static void row_of(claim_row *r, const char *macro, const char *source, const char *fn, const char *gate,
                   const char *fmt)
{
    static claims reg;
    if (!reg.n && claims_registry(&reg)) fail_msg("%s", cs_errmsg());
    const claim_row *known = claims_find(&reg, macro);
    memset(r, 0, sizeof *r);
    if (known) r->param = known->param;
    snprintf(r->macro, sizeof r->macro, "%s", macro);
    snprintf(r->kind, sizeof r->kind, "measured");
    snprintf(r->source, sizeof r->source, "%s", source);
    snprintf(r->function, sizeof r->function, "%s", fn);
    snprintf(r->gate, sizeof r->gate, "%s", gate);
    snprintf(r->format, sizeof r->format, "%s", fmt);
}

static claim_result eval(const char *macro, const char *source, const char *fn, const char *gate)
{
    claim_row r;
    row_of(&r, macro, source, fn, gate,
           strstr(macro, "Seeds") ? "text" : "%.6f"); /* as the registry: a count is text */
    claim_result res;
    claims_eval(&r, &res);
    return res;
}

/* the per-seed error as main-summary reduces it: mean over the unseen spacings in file order */
static double err_of(int seed, int indep, int probe)
{
    double s = 0;
    for (int k = 0; k < 3; k++) s += w1_of(seed, indep, probe, 4 + k);
    return s / 3;
}

static double median_over_seeds(int indep, int probe)
{
    double x[12], m;
    for (int s = 1; s <= 12; s++) x[s - 1] = err_of(s, indep, probe);
    assert_int_equal(stats_median(x, 12, &m), CS_OK);
    return m;
}

static void one_seed_is_pending_with_the_missing_units(void **st)
{
    (void)st;
    const char *dir = fixture("reading_claims_one", 1);
    char src[800];
    snprintf(src, sizeof src, "%s/run_s*_*.tsv", dir);
    claim_result r = eval("MainRel", src, "claim_main_rel", "main.gate:rel_improvement_min");
    assert_int_equal(r.status, VERDICT_PENDING);
    assert_int_equal(r.gate, VERDICT_PENDING);
    assert_non_null(strstr(r.why, "1 of 12 seeds frozen"));
    assert_non_null(strstr(r.why, "missing 22"));
    assert_non_null(strstr(r.why, "s02_joint s02_indep"));
    /* a main/runs.tsv not made yet reads the same units: pending too */
    char runs[800];
    snprintf(runs, sizeof runs, "%s/runs.tsv", dir);
    r = eval("MainGeomRatio", runs, "claim_main_geom_ratio", "main.gate:shuffle_ratio_min");
    assert_int_equal(r.status, VERDICT_PENDING);
    assert_non_null(strstr(r.why, "1 of 12 seeds frozen"));
    r = eval("ExtrapP", src, "claim_extrap_p", "extrapolation.gate:wilcoxon_p_max");
    assert_int_equal(r.status, VERDICT_PENDING);
    /* the blind level needs no run: computed, its precondition pending */
    char base[800];
    snprintf(base, sizeof base, "%s/baselines.tsv", dir);
    r = eval("MainIso", base, "claim_main_iso", "main.gate:joint_over_direction_blind_max");
    assert_int_equal(r.status, VERDICT_PASS);
    ASSERT_NEAR(r.value, (0.6 + 0.8 + 0.95) / 3, 1e-15);
    assert_int_equal(r.gate, VERDICT_PENDING);
    assert_non_null(strstr(r.gate_detail, "1 of 12 seeds frozen"));
    /* descriptive rows over the seeds frozen so far: labelled, never gated */
    r = eval("MainFrozenSeeds", src, "claim_main_sofar", "-");
    assert_int_equal(r.status, VERDICT_PASS);
    assert_string_equal(r.text, "1");
    r = eval("MainFrozenJoint", src, "claim_main_sofar", "-");
    ASSERT_EXACT(r.value, err_of(1, 0, 0));
    assert_int_equal(r.gate, VERDICT_PENDING);
}

static void units_missing_in_the_middle_are_named(void **st)
{
    (void)st;
    const char *dir = fixture("reading_claims_gaps", 12);
    char p[800], src[800];
    snprintf(p, sizeof p, "%s/run_s05_indep.tsv", dir);
    assert_int_equal(unlink(p), 0);
    snprintf(p, sizeof p, "%s/run_s12_joint.tsv", dir);
    assert_int_equal(unlink(p), 0);
    snprintf(src, sizeof src, "%s/run_s*_*.tsv", dir);
    claim_result r = eval("MainP", src, "claim_main_p", "main.gate:wilcoxon_p_max");
    assert_int_equal(r.status, VERDICT_PENDING);
    assert_non_null(strstr(r.why, "10 of 12 seeds frozen"));
    assert_non_null(strstr(r.why, "missing 2: s05_indep s12_joint"));
    r = eval("MainFrozenSeeds", src, "claim_main_sofar", "-");
    assert_string_equal(r.text, "10");
}

static void twelve_seeds_give_the_gated_claims(void **st)
{
    (void)st;
    const char *dir = fixture("reading_claims_full", 12);
    char src[800], base[800];
    snprintf(src, sizeof src, "%s/run_s*_*.tsv", dir);
    snprintf(base, sizeof base, "%s/baselines.tsv", dir);
    const double mj = median_over_seeds(0, 0), mi = median_over_seeds(1, 0), ms = median_over_seeds(0, 1);
    claim_result r = eval("MainRel", src, "claim_main_rel", "main.gate:rel_improvement_min");
    assert_int_equal(r.status, VERDICT_PASS);
    ASSERT_EXACT(r.value, 100.0 * ((mi - mj) / mi));
    assert_int_equal(r.gate, VERDICT_PASS);
    r = eval("MainJoint", src, "claim_main_median", "-");
    ASSERT_EXACT(r.value, mj);
    r = eval("MainP", src, "claim_main_p", "main.gate:wilcoxon_p_max");
    ASSERT_EXACT(r.value, 2.0 / 4096.0);
    assert_int_equal(r.gate, VERDICT_PASS);
    /* the shuffled joint arm barely worse: the precondition fails, a finding */
    r = eval("MainGeomRatio", src, "claim_main_geom_ratio", "main.gate:shuffle_ratio_min");
    ASSERT_EXACT(r.value, ms / mj);
    assert_int_equal(r.gate, VERDICT_FAIL);
    r = eval("MainIso", base, "claim_main_iso", "main.gate:joint_over_direction_blind_max");
    assert_int_equal(r.gate, VERDICT_FAIL); /* joint ~0.42 over blind ~0.78 > 0.5 */
    r = eval("MainFrozenRel", src, "claim_main_sofar", "-");
    ASSERT_EXACT(r.value, 100.0 * (mi - mj) / mi);
    /* the turned-geometry probe over the same seeds: median rotated / median joint */
    r = eval("MainFrozenRotRatio", src, "claim_main_sofar", "-");
    ASSERT_EXACT(r.value, median_over_seeds(0, 2) / mj);
    r = eval("ExtrapLowRel", src, "claim_extrap_rel", "extrapolation.gate:rel_improvement_min");
    assert_int_equal(r.status, VERDICT_PASS);
    double j[12], i[12], a, b;
    for (int s = 1; s <= 12; s++) { j[s - 1] = w1_of(s, 0, 0, 3.0) * 0.8; i[s - 1] = w1_of(s, 1, 0, 3.0) * 0.8; }
    stats_median(j, 12, &a);
    stats_median(i, 12, &b);
    ASSERT_EXACT(r.value, 100.0 * ((b - a) / b));
    assert_int_equal(r.gate, VERDICT_PASS);
    r = eval("MainStepsPerSec", src, "claim_main_meta", "-");
    ASSERT_EXACT(r.value, 13.75); /* median of 8..19 and 8.5..19.5: (13.5 + 14) / 2 */
    r = eval("MainParams", src, "claim_main_meta", "-");
    ASSERT_EXACT(r.value, 159000);
}

/* The unit set and main-summary's runs.tsv give the same claims, bit for bit. */
static void unit_set_equals_main_summary(void **st)
{
    (void)st;
    const char *dir = fixture("reading_claims_summary", 12);
    char root[700], src[800], runs[800], ex[800];
    snprintf(root, sizeof root, "%.*s", (int)(strlen(dir) - strlen("/main")), dir);
    char *argv[] = {"crownshy", "main-summary"};
    mainsum_summary_args a = {.dir = root, .seeds = 12, .argc = 2, .argv = argv};
    assert_int_equal(mainsum_summary(&a), CS_OK);
    snprintf(src, sizeof src, "%s/run_s*_*.tsv", dir);
    snprintf(runs, sizeof runs, "%s/runs.tsv", dir);
    snprintf(ex, sizeof ex, "%s/extrapolation/runs.tsv", root);
    interval_table it;
    assert_int_equal(interval_table_load(PATHS_INTERVALS, &it), CS_OK);
    static const struct { const char *m, *fn; int ex; } k[] = {
        {"MainRel", "claim_main_rel", 0}, {"MainJoint", "claim_main_median", 0}, {"MainIndepHi", "claim_main_range", 0},
        {"MainP", "claim_main_p", 0}, {"MainGeomRatio", "claim_main_geom_ratio", 0}, {"MainRotRatio", "claim_main_probe", 0},
        {"MainGeomRatioIndep", "claim_main_probe", 0}, {"ExtrapLowRel", "claim_extrap_rel", 1}, {"ExtrapHighRel", "claim_extrap_rel", 1},
        {"ExtrapP", "claim_extrap_p", 1},
    };
    for (size_t q = 0; q < sizeof k / sizeof *k; q++) {
        claim_result u = eval(k[q].m, src, k[q].fn, "-"), s = eval(k[q].m, k[q].ex ? ex : runs, k[q].fn, "-");
        if (u.status != VERDICT_PASS || s.status != VERDICT_PASS) fail_msg("%s: %s / %s", k[q].m, u.why, s.why);
        if (u.value != s.value) fail_msg("%s: units %.17g, main-summary %.17g", k[q].m, u.value, s.value);
        /* the seed bootstrap reads the unit set as it reads runs.tsv: the same interval */
        claim_row ru, rs;
        row_of(&ru, k[q].m, src, k[q].fn, "-", "%.6f");
        row_of(&rs, k[q].m, k[q].ex ? ex : runs, k[q].fn, "-", "%.6f");
        claim_interval iu, is;
        cs_status su = interval_eval(&it, &ru, &u, &iu), ss = interval_eval(&it, &rs, &s, &is);
        if (su || ss) fail_msg("%s: interval: %s", k[q].m, cs_errmsg());
        if (!iu.has || !is.has || iu.n != 12)
            fail_msg("%s: interval has %d/%d over %zu seeds: %s", k[q].m, iu.has, is.has, iu.n, iu.why);
        if (iu.lo != is.lo || iu.hi != is.hi)
            fail_msg("%s: interval from the units [%.17g, %.17g], from main-summary [%.17g, %.17g]", k[q].m, iu.lo,
                     iu.hi, is.lo, is.hi);
    }
    interval_table_free(&it);
}

static void extension_map_judges_extension_rows_only(void **st)
{
    (void)st;
    claims c;
    assert_int_equal(claims_registry(&c), CS_OK);
    const claim_row *p = claims_find(&c, "PairMainRel"), *m = claims_find(&c, "MainRel");
    assert_non_null(p);
    assert_non_null(m);
    assert_string_equal(p->gate, "main.gate:rel_improvement_min");
    assert_true(p->gate_map_ext && claims_is_beside(p));
    assert_string_equal(m->gate, "main.gate:rel_improvement_min");
    assert_false(m->gate_map_ext || claims_is_beside(m));
    /* the paper's claims read the paper reading; the pair extension its own
     * units, re-evaluated at the readings' volume */
    assert_non_null(strstr(m->source, "frozen/paper-reading/"));
    assert_string_equal(p->source, "frozen/extension-pair/main/run_s*_*.tsv");
    /* a training choice at the gate's seeds: judged through the same map, by
     * the gate's count of seeds (no seeds of its own), never a paper claim */
    const claim_row *v = claims_find(&c, "MoreStandsMainGeomRatio");
    assert_non_null(v);
    assert_string_equal(v->kind, "variant");
    assert_string_equal(v->gate, "main.gate:shuffle_ratio_min");
    assert_true(v->gate_map_ext && claims_is_beside(v));
    assert_false(v->param.set & PARAM_SEEDS);
    const char *dir = tu_tmpdir("reading_claims_maps");
    char bad[1200], cmd[4000];
    snprintf(bad, sizeof bad, "%s/ext.tsv", dir);
    tu_write(bad, "macro\tgate\nMainJoint\tmain.gate:rel_improvement_min\n");
    assert_int_equal(claims_apply_gate_maps(&c, PATHS_GATE_MAP, bad), CS_EINPUT);
    assert_non_null(strstr(cs_errmsg(), "extension claims only"));
    snprintf(bad, sizeof bad, "%s/main.tsv", dir);
    snprintf(cmd, sizeof cmd, "cp %s %s && printf 'PairMainP\\tmain.gate:wilcoxon_p_max\\n' >> %s", PATHS_GATE_MAP, bad,
             bad);
    assert_int_equal(system(cmd), 0);
    assert_int_equal(claims_apply_gate_maps(&c, bad, PATHS_GATE_MAP_EXT), CS_EINPUT);
    assert_non_null(strstr(cs_errmsg(), PATHS_GATE_MAP_EXT));
    snprintf(bad, sizeof bad, "%s/main_variant.tsv", dir);
    snprintf(cmd, sizeof cmd, "cp %s %s && printf 'MoreEpochsMainP\\tmain.gate:wilcoxon_p_max\\n' >> %s",
             PATHS_GATE_MAP, bad, bad);
    assert_int_equal(system(cmd), 0);
    assert_int_equal(claims_apply_gate_maps(&c, bad, PATHS_GATE_MAP_EXT), CS_EINPUT);
    assert_non_null(strstr(cs_errmsg(), PATHS_GATE_MAP_EXT));
    claims_free(&c);
}

static void comparison_medians_and_ranges(void **st)
{
    (void)st;
    const char *dir = tu_tmpdir("reading_claims_comp");
    char p[700];
    snprintf(p, sizeof p, "%s/dist_summary.tsv", dir);
    tu_write(p, "probe\tsource\tpatches\tmedian_nn_q05\tmedian_nn_q50\tmedian_nn_q95\toverlapping_q05\toverlapping_"
                "q50\toverlapping_q95\tno_overlap_fraction\n"
                "comparison\tteacher\t256\t0.28\t0.30\t0.32\t0\t0\t0\t1\n"
                "comparison\tjoint\t256\t0.23\t0.28\t0.33\t0\t2\t4\t0.46875\n"
                "comparison\tindep\t256\t-0.4\t-0.12\t0.14\t14\t20\t23\t0\n"
                "dart\tteacher\t256\t0.2\t0.23\t0.26\t0\t0\t0\t1\n"
                "dart\tjoint\t256\t-0.3\t-0.14\t0.02\t16\t20\t23\t0\n");
    claim_row r;
    claim_result res;
    row_of(&r, "CompIndepOverlap", p, "claim_comp_overlap", "-", "%.0f");
    claims_eval(&r, &res);
    assert_string_equal(res.text, "20");
    row_of(&r, "PairCompGenOverlapRange", p, "claim_comp_overlap", "-", "text");
    claims_eval(&r, &res);
    assert_string_equal(res.text, "0 to 4");
    row_of(&r, "GenCompIndepKRange", p, "claim_comp_k", "-", "text");
    claims_eval(&r, &res);
    assert_string_equal(res.text, "-0.400 to +0.140");
    row_of(&r, "DartProbeGenK", p, "claim_comp_dart", "-", "%+.3f");
    claims_eval(&r, &res);
    assert_string_equal(res.text, "-0.140");
    row_of(&r, "CompGenNoOverlap", p, "claim_comp_no_overlap", "-", "%.0f");
    claims_eval(&r, &res);
    assert_string_equal(res.text, "47");
}

/* A reading's table not frozen yet is pending; any other missing frozen file fails. */
static void awaited_tables_pend_others_fail(void **st)
{
    (void)st;
    claim_result r = eval("CompGenOverlap", "frozen/paper-reading/comparison/none.tsv", "claim_comp_overlap", "-");
    assert_int_equal(r.status, VERDICT_PENDING);
    assert_non_null(strstr(r.why, "not frozen yet"));
    r = eval("CompGenOverlap", "frozen/comparison/none.tsv", "claim_comp_overlap", "-");
    assert_int_equal(r.status, VERDICT_FAIL);
    /* a reading none of whose units is frozen (every real reading is complete) */
    r = eval("PlainMainJoint", "frozen/model-readings/unrun/main/run_s*_*.tsv", "claim_main_median", "-");
    assert_int_equal(r.status, VERDICT_PENDING);
    assert_non_null(strstr(r.why, "of 4 seeds frozen"));
}

/* The folder of the training choice stands-x4 beside the paper reading of a
 * fixture (dir: its paper-reading/main), made empty. */
static const char *choice_dir(const char *dir)
{
    static char choice[900];
    char cmd[1000];
    snprintf(choice, sizeof choice, "%.*s/generator-sensitivity/stands-x4/main",
             (int)(strlen(dir) - strlen("/paper-reading/main")), dir);
    snprintf(cmd, sizeof cmd, "mkdir -p '%s'", choice);
    assert_int_equal(system(cmd), 0);
    return choice;
}

/* A training choice of the paper reading (generator-sensitivity/<choice>/main/,
 * 4 seeds): each arm's median error over the paper reading's direction-blind
 * level, pending while a unit is missing. The choice's units are the
 * fixture's seeds 1-4; the blind level is (0.6 + 0.8 + 0.95) / 3. */
static void training_choice_over_the_blind_level(void **st)
{
    (void)st;
    const char *dir = fixture("reading_claims_gensens", 1);
    const char *choice = choice_dir(dir);
    char src[1000];
    for (int s = 1; s <= 4; s++) { write_unit(choice, s, 0); if (s < 4) write_unit(choice, s, 1); }
    snprintf(src, sizeof src, "%s/run_s*_*.tsv", choice);
    claim_result r = eval("GenStandsJointBlind", src, "claim_gensens_joint_blind", "-");
    assert_int_equal(r.status, VERDICT_PENDING);
    assert_non_null(strstr(r.why, "s04_indep"));
    /* a descriptive row reads the joint arm, whole, while the independent arm is still running */
    claim_row pr;
    row_of(&pr, "GenStandsJointBlind", src, "claim_gensens_joint_blind", "-", "%.6f");
    snprintf(pr.kind, sizeof pr.kind, "probe");
    claims_eval(&pr, &r);
    assert_int_equal(r.status, VERDICT_PASS);
    assert_non_null(strstr(r.where, "that arm whole"));
    row_of(&pr, "GenStandsMainJoint", src, "claim_main_median", "-", "%.6f");
    snprintf(pr.kind, sizeof pr.kind, "probe");
    claims_eval(&pr, &r);
    assert_int_equal(r.status, VERDICT_PASS);
    ASSERT_EXACT(r.value, (err_of(2, 0, 0) + err_of(3, 0, 0)) / 2);
    row_of(&pr, "GenStandsMainGeomRatio", src, "claim_main_geom_ratio", "-", "%.6f");
    snprintf(pr.kind, sizeof pr.kind, "probe");
    claims_eval(&pr, &r);
    assert_int_equal(r.status, VERDICT_PASS);
    row_of(&pr, "GenStandsIndepBlind", src, "claim_gensens_indep_blind", "-", "%.6f");
    snprintf(pr.kind, sizeof pr.kind, "probe");
    claims_eval(&pr, &r);
    assert_int_equal(r.status, VERDICT_PENDING);
    row_of(&pr, "GenStandsMainIndep", src, "claim_main_median", "-", "%.6f");
    snprintf(pr.kind, sizeof pr.kind, "probe");
    claims_eval(&pr, &r);
    assert_int_equal(r.status, VERDICT_PENDING);
    /* a measured row waits for the whole set */
    r = eval("MainJoint", src, "claim_main_median", "-");
    assert_int_equal(r.status, VERDICT_PENDING);
    write_unit(choice, 4, 1);
    const double blind = (0.6 + 0.8 + 0.95) / 3;
    const double want[2] = {(err_of(2, 0, 0) + err_of(3, 0, 0)) / 2 / blind,
                            (err_of(2, 1, 0) + err_of(3, 1, 0)) / 2 / blind};
    static const char *fn[2] = {"claim_gensens_joint_blind", "claim_gensens_indep_blind"};
    for (int a = 0; a < 2; a++) {
        r = eval(a ? "GenStandsIndepBlind" : "GenStandsJointBlind", src, fn[a], "-");
        assert_int_equal(r.status, VERDICT_PASS);
        if (r.value != want[a]) fail_msg("arm %d: observed %.17g, expected %.17g", a, r.value, want[a]);
    }
}

/* How many seeds a row reads is its params' seeds (or, absent, the gate's
 * preregistered count), never where its units lie: a twelve-seed unit set
 * under generator-sensitivity/ read at four seeds and at twelve; a gated row
 * that names its own seeds refused, naming the row. */
static void seeds_come_from_the_row_not_the_path(void **st)
{
    (void)st;
    const char *dir = fixture("reading_claims_seeds", 1);
    const char *choice = choice_dir(dir);
    char src[1000];
    for (int s = 1; s <= 12; s++) { write_unit(choice, s, 0); write_unit(choice, s, 1); }
    snprintf(src, sizeof src, "%s/run_s*_*.tsv", choice);
    claim_row row;
    claim_result r;
    double x[12], four, twelve;
    for (int s = 1; s <= 12; s++) x[s - 1] = err_of(s, 0, 0);
    assert_int_equal(stats_median(x, 4, &four), CS_OK);
    assert_int_equal(stats_median(x, 12, &twelve), CS_OK);
    assert_true(four != twelve);
    row_of(&row, "SeedsFour", src, "claim_main_median", "-", "%.6f");
    assert_int_equal(claim_params_parse("arm=joint;seeds=4", "claims.tsv", 3, &row.param), CS_OK);
    claims_eval(&row, &r);
    assert_int_equal(r.status, VERDICT_PASS);
    if (r.value != four) fail_msg("seeds=4: observed %.17g, expected %.17g", r.value, four);
    assert_int_equal(claim_params_parse("arm=joint", "claims.tsv", 3, &row.param), CS_OK);
    claims_eval(&row, &r);
    assert_int_equal(r.status, VERDICT_PASS);
    if (r.value != twelve) fail_msg("no seeds (the gate's twelve): observed %.17g, expected %.17g", r.value, twelve);
    /* the choice's direction-blind precondition, judged on the ratio itself at twelve seeds */
    row_of(&row, "MoreStandsMainIso", src, "claim_gensens_joint_blind", "main.gate:joint_over_direction_blind_max",
           "%.6f");
    snprintf(row.kind, sizeof row.kind, "variant");
    claims_eval(&row, &r);
    assert_int_equal(r.status, VERDICT_PASS);
    const double blind = (0.6 + 0.8 + 0.95) / 3;
    if (r.value != twelve / blind)
        fail_msg("MoreStandsMainIso: observed %.17g, expected %.17g", r.value, twelve / blind);
    assert_int_equal(r.gate, VERDICT_FAIL); /* about 0.42 over 0.78 > 0.5 */
    if (r.gate_observed != twelve / blind) fail_msg("judged %.17g, expected %.17g", r.gate_observed, twelve / blind);
    /* its extrapolation gate reads the paper reading's baselines too (the same stands), never pending */
    row_of(&row, "MoreStandsExtrapLowRel", src, "claim_extrap_rel", "extrapolation.gate:rel_improvement_min", "%.6f");
    snprintf(row.kind, sizeof row.kind, "variant");
    claims_eval(&row, &r);
    assert_int_equal(r.status, VERDICT_PASS);
    if (r.gate == VERDICT_PENDING) fail_msg("MoreStandsExtrapLowRel: gate pending: %s", r.gate_detail);
    /* the same four seeds read from the paper reading's own folder: the path chooses nothing */
    snprintf(src, sizeof src, "%s/run_s*_*.tsv", dir);
    row_of(&row, "SeedsOne", src, "claim_main_median", "-", "%.6f");
    assert_int_equal(claim_params_parse("arm=joint;seeds=1", "claims.tsv", 3, &row.param), CS_OK);
    claims_eval(&row, &r);
    assert_int_equal(r.status, VERDICT_PASS);
    if (r.value != err_of(1, 0, 0)) fail_msg("seeds=1: observed %.17g, expected %.17g", r.value, err_of(1, 0, 0));
    row_of(&row, "SeedsGated", src, "claim_main_rel", "main.gate:rel_improvement_min", "%.6f");
    assert_int_equal(claim_params_parse("seeds=1", "claims.tsv", 3, &row.param), CS_OK);
    claims_eval(&row, &r);
    assert_int_equal(r.status, VERDICT_FAIL);
    if (!strstr(r.why, "SeedsGated is gated")) fail_msg("gated row with seeds: '%s'", r.why);
    assert_int_equal(claim_params_parse("arm=joint;seeds=2.5", "claims.tsv", 3, &row.param), CS_OK);
    snprintf(row.gate, sizeof row.gate, "-");
    snprintf(row.function, sizeof row.function, "claim_main_median");
    claims_eval(&row, &r);
    assert_int_equal(r.status, VERDICT_FAIL);
    if (!strstr(r.why, "seeds=a whole number")) fail_msg("seeds=2.5: '%s'", r.why);
}

/* What the paper's shuffle ratio requires of a teacher (src/claims/perfect.c)
 * from a sensitivity table with three teachers' shuffled levels (other
 * quantities' rows ignored), against the registry's paper values 0.415 m
 * (MainJoint) and 2.50 (MainGeomRatio). */
static void perfect_generator_levels(void **st)
{
    (void)st;
    const char *dir = tu_tmpdir("reading_claims_perfect");
    char src[800];
    snprintf(src, sizeof src, "%s/summary.tsv", dir);
    tu_write(src, "quantity\tchoice\tx\tvalue\tpaper\trel_diff\tsource\n"
                  "MainIso\tcentre\tnan\t0.9\tnan\tnan\tc\n"
                  "MainShufTeach\tcentre\tnan\t0.45\tnan\tnan\tc\n"
                  "MainShufTeach\tcrown_R\t3\t0.40\tnan\tnan\tc\n"
                  "MainShufTeach\tcrown_R\t5\t0.70\tnan\tnan\tc\n");
    static const struct { const char *fn; double want; } c[] = {
        {"claim_perfect_shuf_lo", 0.40}, {"claim_perfect_shuf_hi", 0.70}, {"claim_perfect_shuf_needed", (2.50 - 1.0) * 0.415},
        {"claim_perfect_bound_max", 1.0 + 0.70 / 0.415}, {"claim_perfect_reaching", 1}, {"claim_perfect_teachers", 3},
    };
    for (size_t i = 0; i < sizeof c / sizeof *c; i++) {
        claim_result r = eval("PerfectX", src, c[i].fn, "-");
        assert_int_equal(r.status, VERDICT_PASS);
        if (r.value != c[i].want) fail_msg("%s: observed %.17g, expected %.17g", c[i].fn, r.value, c[i].want);
    }
    /* a level that is not positive is refused, naming the line */
    tu_write(src,
             "quantity\tchoice\tx\tvalue\tpaper\trel_diff\tsource\nMainShufTeach\tcentre\tnan\tnan\tnan\tnan\tc\n");
    claim_result r = eval("PerfectX", src, "claim_perfect_shuf_hi", "-");
    assert_int_equal(r.status, VERDICT_FAIL);
    assert_non_null(strstr(r.why, "summary.tsv:2"));
}

/* What a generator uses (src/claims/claim_probe.c): a reading's probe tables
 * for seeds 1-4 give the median probed error over the median unprobed one,
 * pending while a seed is missing (the registry row's seeds=4); the teacher's table gives its level. */
static void generator_probe_ratios(void **st)
{
    (void)st;
    const char *dir = tu_tmpdir("reading_claims_probes");
    char p[900], src[900];
    /* seed s: none 0.40 + 0.01 s at every spacing, self twice that at 4 m, 2.5 x at 5 and 6 m */
    for (int s = 1; s <= 4; s++) {
        const double e = 0.40 + 0.01 * s;
        char buf[1024];
        snprintf(buf, sizeof buf, "spacing\tprobe\tw1\tn_gen\tn_teacher\n"
                 "4\tnone\t%.17g\t256\t1000\n4\tself\t%.17g\t256\t1000\n5\tnone\t%.17g\t256\t1000\n5\tself\t%.17g\t256\t1000\n"
                 "6\tnone\t%.17g\t256\t1000\n6\tself\t%.17g\t256\t1000\n", e, 2 * e, e, 2.5 * e, e, 2.5 * e);
        snprintf(p, sizeof p, "%s/probes_s%02d_joint.tsv", dir, s);
        if (s < 4) tu_write(p, buf);
        else {
            snprintf(src, sizeof src, "%s/probes_s*_joint.tsv", dir);
            claim_result r = eval("ProbePaperSelfJoint", src, "claim_probe_self", "-");
            assert_int_equal(r.status, VERDICT_PENDING);
            assert_non_null(strstr(r.why, "3 of 4 seeds frozen; missing s04"));
            tu_write(p, buf);
        }
    }
    claim_result r = eval("ProbePaperSelfJoint", src, "claim_probe_self", "-");
    assert_int_equal(r.status, VERDICT_PASS);
    /* per seed the self error is (2 + 2.5 + 2.5) / 3 e; medians over seeds of e = 0.425 */
    ASSERT_NEAR(r.value, 7.0 / 3.0, 1e-12);
    r = eval("ProbePaperNnSwapJoint", src, "claim_probe_nnswap", "-");
    assert_int_equal(r.status, VERDICT_FAIL);
    assert_non_null(strstr(r.why, "no rows of the nnswap probe"));
    snprintf(p, sizeof p, "%s/probes.tsv", dir);
    tu_write(p, "spacing\tprobe\tw1\tn_gen\tn_teacher\n4\trot90\t0.3\t1000\t1000\n5\trot90\t0."
                "4\t1000\t1000\n6\trot90\t0.5\t1000\t1000\n");
    r = eval("ProbeTeacherRotNinety", p, "claim_probe_teacher_rot90", "-");
    assert_int_equal(r.status, VERDICT_PASS);
    ASSERT_NEAR(r.value, 0.4, 1e-15);
}

int main(void)
{
    const struct CMUnitTest t[] = {
        cmocka_unit_test(one_seed_is_pending_with_the_missing_units),
        cmocka_unit_test(units_missing_in_the_middle_are_named),
        cmocka_unit_test(twelve_seeds_give_the_gated_claims),
        cmocka_unit_test(unit_set_equals_main_summary),
        cmocka_unit_test(extension_map_judges_extension_rows_only),
        cmocka_unit_test(comparison_medians_and_ranges),
        cmocka_unit_test(awaited_tables_pend_others_fail),
        cmocka_unit_test(training_choice_over_the_blind_level),
        cmocka_unit_test(seeds_come_from_the_row_not_the_path),
        cmocka_unit_test(perfect_generator_levels),
        cmocka_unit_test(generator_probe_ratios),
    };
    return cmocka_run_group_tests(t, NULL, NULL);
}
