/* Tests for src/forest/teacher.c (design.md §4): exact targets for a lone tree and for
 * coupling off, no overlap over random stands at every spacing and die-back
 * of the sweeps, beta = 0 gaps within one step, bit-identical repeats, the
 * self-check itself, and the perturbation rule (order and vigour by height).
 * teacher-2 (mutual abrasion): two spikes meeting tip to tip, where both
 * contacting sectors lose exactly beta of their own length and freeze; the
 * teacher-1 switch still gives the one-sided rule on the same pair (the
 * entered crown regrows); the two further die-back readings (the contact arc;
 * beta of the target length) and the start fraction on the same pair; worst
 * overlap exactly 0 on full 144-tree stands under every rule. */
#include "testutil.h"
#include "teacher.h"
#include "stand.h"
#include "estimator.h"
#include "crown.h"

static void lobed(double *t, double R, double a, int k, double phi)
{
    crown_draw c = {.h = 25.0, .R = R, .a = a, .k = k, .phi = phi};
    crown_target(&c, t);
}

static void test_lone_tree_reaches_its_target_exactly(void **st)
{
    (void)st;
    double x = 10.0, y = 10.0, h = 21.3, R = 3.3, t[CROWN_NSEC], r[CROWN_NSEC];
    lobed(t, R, 0.17, 4, 1.1);
    teacher_stand s = {1, &x, &y, &h, &R, t};
    teacher_params p;
    teacher_params_default(&p);
    teacher_info inf;
    assert_int_equal(teacher_grow(&s, &p, r, &inf), CS_OK);
    for (int k = 0; k < CROWN_NSEC; k++) ASSERT_EXACT(r[k], t[k]);
    assert_int_equal(inf.frozen, 0);
    ASSERT_EXACT(inf.step, 3.3 / 48.0);
}

static void test_coupling_off_equals_the_targets(void **st)
{
    (void)st;
    stand *sd = NULL;
    assert_int_equal(stand_alloc(&sd, stems_lattice, 3.5, 42.0, 0.04, "test/teacher", 1), CS_OK);
    teacher_stand v;
    stand_view(sd, &v);
    double *r = malloc(v.n * CROWN_NSEC * sizeof *r);
    teacher_params p;
    teacher_params_default(&p);
    p.coupled = 0;
    assert_int_equal(teacher_grow(&v, &p, r, NULL), CS_OK);
    assert_memory_equal(r, sd->rstar, v.n * CROWN_NSEC * sizeof *r);
    /* and at 3.5 m those targets interpenetrate */
    double w = 0.0;
    assert_int_equal(teacher_worst_overlap(v.x, v.y, r, v.n, &w), CS_OK);
    assert_true(w > 1.0);
    free(r);
    stand_free(sd);
}

static void test_two_trees_meet_between_their_stems(void **st)
{
    (void)st;
    /* Equal heights, circles of 3 m, stems 4 m apart: growth stops near 2 m each. */
    double x[2] = {0.0, 4.0}, y[2] = {0.0, 0.0}, h[2] = {25.0, 25.0}, R[2] = {3.0, 3.0};
    double t[2 * CROWN_NSEC], r[2 * CROWN_NSEC];
    lobed(t, 3.0, 0.0, 2, 0.0);
    lobed(t + CROWN_NSEC, 3.0, 0.0, 2, 0.0);
    teacher_stand s = {2, x, y, h, R, t};
    teacher_params p;
    teacher_params_default(&p);
    p.beta = 0.0;
    teacher_info inf;
    assert_int_equal(teacher_grow(&s, &p, r, &inf), CS_OK);
    double g = est_clearance(x[0], y[0], r, x[1], y[1], r + CROWN_NSEC);
    assert_true(g >= 0.0);
    if (!(g <= inf.step)) fail_msg("beta=0 gap %.17g wider than one step %.17g", g, inf.step);
    /* Far side untouched: sector 12 of tree 0 reaches its target. */
    ASSERT_EXACT(r[12], 3.0);
}

static void test_taller_tree_claims_more_of_the_contested_space(void **st)
{
    (void)st;
    double x[2] = {0.0, 4.0}, y[2] = {0.0, 0.0}, h[2] = {32.0, 18.0}, R[2] = {3.0, 3.0};
    double t[2 * CROWN_NSEC], r[2 * CROWN_NSEC];
    lobed(t, 3.0, 0.0, 2, 0.0);
    lobed(t + CROWN_NSEC, 3.0, 0.0, 2, 0.0);
    teacher_stand s = {2, x, y, h, R, t};
    teacher_params p;
    teacher_params_default(&p);
    assert_int_equal(teacher_grow(&s, &p, r, NULL), CS_OK);
    /* Sector 0 of the tall tree faces sector 12 of the short one. */
    if (!(r[0] > r[CROWN_NSEC + 12] + 0.3))
        fail_msg("tall %.17g vs short %.17g", r[0], r[CROWN_NSEC + 12]);
}

static void test_no_overlap_at_every_spacing_and_dieback(void **st)
{
    (void)st;
    const double spacings[5] = {3.0, 3.5, 4.5, 5.5, 6.5};
    const double betas[4] = {0.0, 0.03, 0.06, 0.09};
    double worst = 0.0;
    for (int a = 0; a < 5; a++)
        for (int b = 0; b < 4; b++) {
            stand *sd = NULL;
            /* 8 d footprints (~64 trees) keep the test fast; hard-core on odd cells. */
            const stems_type *kind = ((a + b) & 1) ? stems_hardcore : stems_lattice;
            double shape = kind == stems_hardcore ? 0.5 : 0.04;
            assert_int_equal(stand_alloc(&sd, kind, spacings[a], 8.0 * spacings[a], shape, "test/overlap", (unsigned)b),
                             CS_OK);
            teacher_stand v;
            stand_view(sd, &v);
            double *r = malloc(v.n * CROWN_NSEC * sizeof *r);
            teacher_params p;
            teacher_params_default(&p);
            p.beta = betas[b];
            teacher_info inf;
            cs_status rc = teacher_grow(&v, &p, r, &inf);
            if (rc) fail_msg("d=%g beta=%g: %s", spacings[a], betas[b], cs_errmsg());
            if (inf.worst_overlap > worst) worst = inf.worst_overlap;
            /* Independent of the self-check: every pair's Eq. 5 clearance >= 0. */
            for (size_t i = 0; i < v.n; i++)
                for (size_t j = i + 1; j < v.n; j++) {
                    double g = est_clearance(v.x[i], v.y[i], r + i * CROWN_NSEC, v.x[j], v.y[j], r + j * CROWN_NSEC);
                    if (g < -1e-9) fail_msg("d=%g beta=%g pair %zu,%zu g=%.17g", spacings[a], betas[b], i, j, g);
                }
            free(r);
            stand_free(sd);
        }
    assert_true(worst <= 1e-9);
}

static void test_beta_zero_leaves_gaps_within_one_step(void **st)
{
    (void)st;
    stand *sd = NULL;
    assert_int_equal(stand_alloc(&sd, stems_lattice, 3.5, 42.0, 0.04, "test/beta0", 0), CS_OK);
    teacher_stand v;
    stand_view(sd, &v);
    double *r = malloc(v.n * CROWN_NSEC * sizeof *r);
    double *g = malloc(v.n * sizeof *g);
    teacher_params p;
    teacher_params_default(&p);
    p.beta = 0.0;
    teacher_info inf;
    assert_int_equal(teacher_grow(&v, &p, r, &inf), CS_OK);
    size_t m = 0;
    for (size_t i = 0; i < v.n; i++) {
        if (!stems_interior(sd->s, i)) continue;
        assert_int_equal(est_knn_clearance(v.x, v.y, r, v.n, i, 1, &g[m]), CS_OK);
        m++;
    }
    double med = 0.0;
    assert_int_equal(est_median(g, m, &med), CS_OK);
    /* The fastest tree's step is at most Delta * 38 / hbar. */
    double maxstep = inf.step * 38.0 / inf.hbar;
    if (!(med >= 0.0 && med <= maxstep)) fail_msg("median k1 gap %.17g, one step %.17g", med, maxstep);
    free(r); free(g);
    stand_free(sd);
}

static void test_growth_is_bit_identical_on_repeat(void **st)
{
    (void)st;
    stand *sd = NULL;
    assert_int_equal(stand_alloc(&sd, stems_hardcore, 4.5, 36.0, 0.5, "test/repeat", 2), CS_OK);
    teacher_stand v;
    stand_view(sd, &v);
    size_t bytes = v.n * CROWN_NSEC * sizeof(double);
    double *a = malloc(bytes), *b = malloc(bytes);
    teacher_params p;
    teacher_params_default(&p);
    assert_int_equal(teacher_grow(&v, &p, a, NULL), CS_OK);
    assert_int_equal(teacher_grow(&v, &p, b, NULL), CS_OK);
    assert_memory_equal(a, b, bytes);
    free(a); free(b);
    stand_free(sd);
}

static void test_perturbation_keeps_hbar_and_moves_neighbours(void **st)
{
    (void)st;
    stand *sd = NULL;
    assert_int_equal(stand_alloc(&sd, stems_lattice, 4.5, 54.0, 0.04, "test/perturb", 0), CS_OK);
    teacher_stand v;
    stand_view(sd, &v);
    size_t n = v.n, bytes = n * CROWN_NSEC * sizeof(double);
    double *a = malloc(bytes), *b = malloc(bytes), *h2 = malloc(n * sizeof *h2);
    teacher_params p;
    teacher_params_default(&p);
    teacher_info ia, ib;
    assert_int_equal(teacher_grow(&v, &p, a, &ia), CS_OK);
    /* The interior tree nearest the centre, 30% taller, hbar kept. */
    size_t f = 0;
    double best = 1e9;
    for (size_t i = 0; i < n; i++) {
        double dd = hypot(v.x[i] - 27.0, v.y[i] - 27.0);
        if (dd < best) { best = dd; f = i; }
    }
    memcpy(h2, v.h, n * sizeof *h2);
    h2[f] *= 1.3;
    v.h = h2;
    p.hbar = ia.hbar;
    assert_int_equal(teacher_grow(&v, &p, b, &ib), CS_OK);
    ASSERT_EXACT(ib.hbar, ia.hbar);
    int moved = 0;
    for (int k = 1; k <= 4; k++) {
        long j = est_knn(v.x, v.y, n, f, k);
        for (int s = 0; s < CROWN_NSEC; s++)
            if (fabs(a[(size_t)j * CROWN_NSEC + s] - b[(size_t)j * CROWN_NSEC + s]) > 1e-6) { moved++; break; }
    }
    assert_true(moved >= 2);
    free(a); free(b); free(h2);
    stand_free(sd);
}

static void test_self_check_measures_a_known_overlap(void **st)
{
    (void)st;
    double x[2] = {0.0, 1.5}, y[2] = {0.0, 0.0}, r[2 * CROWN_NSEC], w = 0.0;
    for (int k = 0; k < 2 * CROWN_NSEC; k++) r[k] = 1.0;
    assert_int_equal(teacher_worst_overlap(x, y, r, 2, &w), CS_OK);
    ASSERT_NEAR(w, 0.5, 1e-15);
    x[1] = 2.25;
    assert_int_equal(teacher_worst_overlap(x, y, r, 2, &w), CS_OK);
    ASSERT_EXACT(w, 0.0);
}

static void test_stems_closer_than_the_starting_crowns_are_unbuildable(void **st)
{
    (void)st;
    /* Starting radius 0.05 * 4 = 0.2 m each; stems 0.3 m apart overlap by 0.1 m. */
    double x[2] = {5.0, 5.3}, y[2] = {5.0, 5.0}, h[2] = {25.0, 20.0}, R[2] = {4.0, 4.0};
    double t[2 * CROWN_NSEC], r[2 * CROWN_NSEC];
    lobed(t, 4.0, 0.0, 2, 0.0);
    lobed(t + CROWN_NSEC, 4.0, 0.0, 2, 0.0);
    teacher_stand s = {2, x, y, h, R, t};
    teacher_params p;
    teacher_params_default(&p);
    cs_errclear();
    assert_int_equal(teacher_grow(&s, &p, r, NULL), CS_EINPUT);
    assert_non_null(strstr(cs_errmsg(), "unbuildable"));
    /* The uncoupled twin has no contact rule and grows. */
    p.coupled = 0;
    assert_int_equal(teacher_grow(&s, &p, r, NULL), CS_OK);
}

static void test_frozen_output_marks_contact_sectors_only(void **st)
{
    (void)st;
    double x[2] = {0.0, 4.0}, y[2] = {0.0, 0.0}, h[2] = {25.0, 25.0}, R[2] = {3.0, 3.0};
    double t[2 * CROWN_NSEC], r[2 * CROWN_NSEC];
    unsigned char fz[2 * CROWN_NSEC];
    lobed(t, 3.0, 0.0, 2, 0.0);
    lobed(t + CROWN_NSEC, 3.0, 0.0, 2, 0.0);
    teacher_stand s = {2, x, y, h, R, t};
    teacher_params p;
    teacher_params_default(&p);
    p.frozen_out = fz;
    teacher_info inf;
    assert_int_equal(teacher_grow(&s, &p, r, &inf), CS_OK);
    assert_int_equal(fz[0], 1);              /* tree 0 facing east, toward tree 1 */
    assert_int_equal(fz[12], 0);             /* tree 0 facing west: free */
    assert_int_equal(fz[CROWN_NSEC + 12], 1); /* tree 1 facing west, toward tree 0 */
    size_t cnt = 0;
    for (int k = 0; k < 2 * CROWN_NSEC; k++) cnt += fz[k];
    assert_int_equal(cnt, inf.frozen);
}

static void test_bad_parameters_are_rejected(void **st)
{
    (void)st;
    double x = 0, y = 0, h = 20, R = 3, t[CROWN_NSEC], r[CROWN_NSEC];
    lobed(t, 3.0, 0.1, 3, 0.0);
    teacher_stand s = {1, &x, &y, &h, &R, t};
    teacher_params p;
    teacher_params_default(&p);
    p.beta = 1.0;
    assert_int_equal(teacher_grow(&s, &p, r, NULL), CS_EINPUT);
    teacher_params_default(&p);
    p.nres = 0;
    assert_int_equal(teacher_grow(&s, &p, r, NULL), CS_EINPUT);
}

/* ---- teacher-2: mutual abrasion (design.md §4) -------------------------
 * Two spikes meeting tip to tip: tree 0 has target 3 m in sector 0 (east) and
 * 0.5 m elsewhere, tree 1 (4 m east) 3 m in sector 12 (west), 0.5 m elsewhere.
 * Equal heights, so both step by Delta = 3/48 = 0.0625 m per round (exact)
 * from 0.05 * 3 m, tree 0 first (ties by index). After 29 rounds both spikes
 * are at v29 = 1.9625 (sum 3.925 m < 4 m); in round 30 tree 0 reaches v30 =
 * 2.025 legally (2.025 + 1.9625 = 3.9875 < 4), then tree 1's proposal 2.025
 * would enter tree 0 (4.05 > 4): the contact. The flanks (0.5 m) sit at target
 * long before, so the spikes are the only sectors that can ever touch. */
static void spikes(double *t)
{
    for (int k = 0; k < 2 * CROWN_NSEC; k++) t[k] = 0.5;
    t[0] = 3.0;              /* tree 0, sector 0 (east, toward tree 1) */
    t[CROWN_NSEC + 12] = 3.0; /* tree 1, sector 12 (west, toward tree 0) */
}

/* v_k with the teacher's own arithmetic: r = f r* (f = 0.05 unless a start
 * fraction is given), then r <- r + Delta. */
static double spike_len_from(double f, int k)
{
    double v = f * 3.0;
    for (int q = 0; q < k; q++) v = fmin(v + 3.0 / 48.0, 3.0);
    return v;
}
static double spike_len(int k) { return spike_len_from(0.05, k); }

/* The spike pair grown with parameters p (frozen output and step checked). */
static void grow_spikes_with(teacher_params *p, double *r, unsigned char *fz, teacher_info *inf)
{
    double x[2] = {0.0, 4.0}, y[2] = {0.0, 0.0}, h[2] = {25.0, 25.0}, R[2] = {3.0, 3.0};
    double t[2 * CROWN_NSEC];
    spikes(t);
    teacher_stand s = {2, x, y, h, R, t};
    p->frozen_out = fz;
    assert_int_equal(teacher_grow(&s, p, r, inf), CS_OK);
    ASSERT_EXACT(inf->step, 0.0625);
    ASSERT_EXACT(inf->worst_overlap, 0.0);
}

static void grow_spikes(int one_sided, double *r, unsigned char *fz, teacher_info *inf)
{
    double x[2] = {0.0, 4.0}, y[2] = {0.0, 0.0}, h[2] = {25.0, 25.0}, R[2] = {3.0, 3.0};
    double t[2 * CROWN_NSEC];
    spikes(t);
    teacher_stand s = {2, x, y, h, R, t};
    teacher_params p;
    teacher_params_default(&p);
    p.one_sided = one_sided;
    p.frozen_out = fz;
    assert_int_equal(teacher_grow(&s, &p, r, inf), CS_OK);
    ASSERT_EXACT(inf->step, 0.0625);
    ASSERT_EXACT(inf->worst_overlap, 0.0);
    /* The flanks never touch: every other sector ends at its target, unfrozen. */
    for (int k = 0; k < 2 * CROWN_NSEC; k++) {
        if (k == 0 || k == CROWN_NSEC + 12) continue;
        ASSERT_EXACT(r[k], t[k]);
        assert_int_equal(fz[k], 0);
    }
}

static void test_mutual_abrasion_both_sectors_die_back_by_beta_of_their_own_length(void **st)
{
    (void)st;
    double r[2 * CROWN_NSEC];
    unsigned char fz[2 * CROWN_NSEC];
    teacher_info inf;
    grow_spikes(0, r, fz, &inf);
    const double beta = 0.06; /* the default */
    double v29 = spike_len(29), v30 = spike_len(30);
    ASSERT_EXACT(v29, 1.9625);
    ASSERT_EXACT(v30, 2.025);
    /* Tree 1 (the one whose proposal made contact) loses beta of its 1.9625 m,
     * tree 0 (the crown it would have entered) beta of its own 2.025 m. */
    ASSERT_EXACT(r[CROWN_NSEC + 12], (1.0 - beta) * v29);
    ASSERT_EXACT(r[0], (1.0 - beta) * v30);
    assert_int_equal(fz[CROWN_NSEC + 12], 1);
    assert_int_equal(fz[0], 1);
    assert_int_equal(inf.frozen, 2);
    /* Both frozen for good: the gap stays open at 4 - 0.94 (1.9625 + 2.025). */
    double g = est_clearance(0.0, 0.0, r, 4.0, 0.0, r + CROWN_NSEC);
    ASSERT_NEAR(g, 4.0 - (1.0 - beta) * (v29 + v30), 1e-12);
    assert_string_equal(teacher_version(&(teacher_params){.one_sided = 0}), "teacher-2");
}

static void test_one_sided_switch_keeps_the_one_sided_rule(void **st)
{
    (void)st;
    double r[2 * CROWN_NSEC];
    unsigned char fz[2 * CROWN_NSEC];
    teacher_info inf;
    grow_spikes(1, r, fz, &inf);
    const double beta = 0.06;
    /* Only tree 1's sector dies back (to 0.94 * 1.9625 = 1.84475); tree 0's
     * spike is untouched and regrows into the space given up: v31 + 1.84475 =
     * 3.93225 and v32 + 1.84475 = 3.99475 are legal, v33 = 2.2125 is not, so
     * tree 0 freezes at 0.94 * v32 on its own contact. */
    ASSERT_EXACT(r[CROWN_NSEC + 12], (1.0 - beta) * spike_len(29));
    ASSERT_EXACT(r[0], (1.0 - beta) * spike_len(32));
    assert_int_equal(fz[CROWN_NSEC + 12], 1);
    assert_int_equal(fz[0], 1);
    assert_int_equal(inf.frozen, 2);
    teacher_params p;
    teacher_params_default(&p);
    assert_int_equal(p.one_sided, 0);
    assert_string_equal(teacher_version(&p), "teacher-2");
    assert_string_equal(teacher_version(&p), TEACHER_VERSION);
    p.one_sided = 1;
    assert_string_equal(teacher_version(&p), "teacher-1");
}

/* Worst overlap 0 on full 144-tree stands (12 d footprints) under teacher-2,
 * lattice and hard-core, at the closest, the figure and a wide spacing and at
 * die-backs 0 (freeze without retreat), 0.03, 0.06 and 0.09. Independent of
 * the self-check: every pair's Eq. 5 clearance >= 0. */
/* Neighbouring-sector reading: the contacting sector and its two neighbours
 * of each crown in the contact die back by beta of their own length and
 * freeze: tree 1's sectors 11, 12, 13 and tree 0's sectors 23, 0, 1. */
static void test_neighbour_dieback_abrades_the_contact_arc_of_both_crowns(void **st)
{
    (void)st;
    double r[2 * CROWN_NSEC];
    unsigned char fz[2 * CROWN_NSEC];
    teacher_info inf;
    teacher_params p;
    teacher_params_default(&p);
    p.dieback = TEACHER_DIEBACK_NEIGHBOURS;
    grow_spikes_with(&p, r, fz, &inf);
    const double b = 1.0 - 0.06;
    const int arc[6] = {23, 0, 1, CROWN_NSEC + 11, CROWN_NSEC + 12, CROWN_NSEC + 13};
    ASSERT_EXACT(r[CROWN_NSEC + 12], b * spike_len(29));
    ASSERT_EXACT(r[0], b * spike_len(30));
    ASSERT_EXACT(r[1], b * 0.5);
    ASSERT_EXACT(r[23], b * 0.5);
    ASSERT_EXACT(r[CROWN_NSEC + 11], b * 0.5);
    ASSERT_EXACT(r[CROWN_NSEC + 13], b * 0.5);
    for (int q = 0; q < 6; q++) assert_int_equal(fz[arc[q]], 1);
    assert_int_equal(inf.frozen, 6);
    double t[2 * CROWN_NSEC];
    spikes(t);
    for (int k = 0; k < 2 * CROWN_NSEC; k++) {
        int in_arc = 0;
        for (int q = 0; q < 6; q++) in_arc |= k == arc[q];
        if (in_arc) continue;
        ASSERT_EXACT(r[k], t[k]);
        assert_int_equal(fz[k], 0);
    }
    assert_string_equal(teacher_version(&p), "teacher-2-arc");
}

/* Target-length reading: each contacting sector loses beta of its target
 * (3 m), not of its own length: 0.18 m from 1.9625 and from 2.025. */
static void test_target_dieback_removes_beta_of_the_target_length(void **st)
{
    (void)st;
    double r[2 * CROWN_NSEC];
    unsigned char fz[2 * CROWN_NSEC];
    teacher_info inf;
    teacher_params p;
    teacher_params_default(&p);
    p.dieback = TEACHER_DIEBACK_TARGET;
    grow_spikes_with(&p, r, fz, &inf);
    ASSERT_EXACT(r[CROWN_NSEC + 12], spike_len(29) - 0.06 * 3.0);
    ASSERT_EXACT(r[0], spike_len(30) - 0.06 * 3.0);
    assert_int_equal(fz[CROWN_NSEC + 12], 1);
    assert_int_equal(fz[0], 1);
    assert_int_equal(inf.frozen, 2);
    assert_string_equal(teacher_version(&p), "teacher-2-target");
    p.one_sided = 1;
    assert_string_equal(teacher_version(&p), "teacher-1-target");
}

/* Start radius: from 0.1 r* the spikes are at 0.3 + 0.0625 k; after 27
 * rounds both stand at v27 (sum 3.975 < 4) and in round 28 tree 0's own
 * proposal v28 would enter tree 1: both lose beta of v27. The default 0.05
 * grows bit-identically to an explicit 0.05, and a fraction outside (0, 1]
 * is refused. */
static void test_start_fraction_sets_the_starting_crowns(void **st)
{
    (void)st;
    double r[2 * CROWN_NSEC];
    unsigned char fz[2 * CROWN_NSEC];
    teacher_info inf;
    teacher_params p;
    teacher_params_default(&p);
    ASSERT_EXACT(p.start_frac, 0.05);
    p.start_frac = 0.1;
    grow_spikes_with(&p, r, fz, &inf);
    ASSERT_EXACT(r[0], 0.94 * spike_len_from(0.1, 27));
    ASSERT_EXACT(r[CROWN_NSEC + 12], 0.94 * spike_len_from(0.1, 27));
    assert_int_equal(inf.frozen, 2);
    assert_string_equal(teacher_version(&p), "teacher-2");

    stand *sd = NULL;
    assert_int_equal(stand_alloc(&sd, stems_lattice, 3.5, 42.0, 0.04, "test/startfrac", 3), CS_OK);
    teacher_stand v;
    stand_view(sd, &v);
    double *ra = malloc(v.n * CROWN_NSEC * sizeof *ra), *rb = malloc(v.n * CROWN_NSEC * sizeof *rb);
    teacher_params_default(&p);
    assert_int_equal(teacher_grow(&v, &p, ra, NULL), CS_OK);
    p.start_frac = 0.05;
    assert_int_equal(teacher_grow(&v, &p, rb, NULL), CS_OK);
    assert_memory_equal(ra, rb, v.n * CROWN_NSEC * sizeof *ra);
    p.start_frac = 0.2;
    assert_int_equal(teacher_grow(&v, &p, rb, NULL), CS_OK);
    assert_true(memcmp(ra, rb, v.n * CROWN_NSEC * sizeof *ra) != 0);
    const double bad[3] = {0.0, -0.1, 1.5};
    for (int q = 0; q < 3; q++) {
        p.start_frac = bad[q];
        assert_int_equal(teacher_grow(&v, &p, rb, NULL), CS_EINPUT);
    }
    teacher_params_default(&p);
    p.dieback = (teacher_dieback)7;
    assert_int_equal(teacher_grow(&v, &p, rb, NULL), CS_EINPUT);
    free(ra);
    free(rb);
    stand_free(sd);
}

/* The two further die-back readings keep the no-overlap guarantee on full
 * 144-tree stands (lattice and hard-core at 3.5 m, beta 0.06 and 0.09). */
static void test_dieback_readings_never_overlap_on_full_stands(void **st)
{
    (void)st;
    const teacher_dieback rules[2] = {TEACHER_DIEBACK_NEIGHBOURS, TEACHER_DIEBACK_TARGET};
    const double betas[2] = {0.06, 0.09};
    for (int a = 0; a < 2; a++)
        for (int b = 0; b < 2; b++)
            for (int kind = 0; kind < 2; kind++) {
                stand *sd = NULL;
                assert_int_equal(stand_alloc(&sd, kind ? stems_hardcore : stems_lattice, 3.5, 42.0,
                                             kind ? 0.5 : 0.04, "test/dieback", (unsigned)b), CS_OK);
                teacher_stand v;
                stand_view(sd, &v);
                double *r = malloc(v.n * CROWN_NSEC * sizeof *r);
                teacher_params p;
                teacher_params_default(&p);
                p.dieback = rules[a];
                p.beta = betas[b];
                teacher_info inf;
                if (teacher_grow(&v, &p, r, &inf))
                    fail_msg("%s beta=%g: %s", teacher_version(&p), betas[b], cs_errmsg());
                if (!(inf.frozen > 0)) fail_msg("%s: no contact at all", teacher_version(&p));
                ASSERT_EXACT(inf.worst_overlap, 0.0);
                free(r);
                stand_free(sd);
            }
}

static void test_mutual_abrasion_never_overlaps_on_full_stands(void **st)
{
    (void)st;
    const double spacings[3] = {3.0, 3.5, 5.5};
    const double betas[4] = {0.0, 0.03, 0.06, 0.09};
    double worst = 0.0;
    size_t stands = 0;
    for (int a = 0; a < 3; a++)
        for (int b = 0; b < 4; b++)
            for (int kind = 0; kind < 2; kind++) {
                stand *sd = NULL;
                const stems_type *sk = kind ? stems_hardcore : stems_lattice;
                double shape = kind ? 0.5 : 0.04;
                assert_int_equal(
                    stand_alloc(&sd, sk, spacings[a], 12.0 * spacings[a], shape, "test/mutual", (unsigned)b), CS_OK);
                teacher_stand v;
                stand_view(sd, &v);
                double *r = malloc(v.n * CROWN_NSEC * sizeof *r);
                teacher_params p;
                teacher_params_default(&p);
                p.beta = betas[b];
                teacher_info inf;
                cs_status rc = teacher_grow(&v, &p, r, &inf);
                if (rc)
                    fail_msg("%s d=%g beta=%g: %s", kind ? "hardcore" : "lattice", spacings[a], betas[b], cs_errmsg());
                if (inf.worst_overlap > worst) worst = inf.worst_overlap;
                if (!(inf.frozen > 0)) fail_msg("d=%g beta=%g: no contact at all", spacings[a], betas[b]);
                for (size_t i = 0; i < v.n; i++)
                    for (size_t j = i + 1; j < v.n; j++) {
                        double g =
                            est_clearance(v.x[i], v.y[i], r + i * CROWN_NSEC, v.x[j], v.y[j], r + j * CROWN_NSEC);
                        if (g < -1e-9) fail_msg("d=%g beta=%g pair %zu,%zu g=%.17g", spacings[a], betas[b], i, j, g);
                    }
                stands++;
                free(r);
                stand_free(sd);
            }
    if (!(worst <= 1e-9)) fail_msg("worst overlap %.17g m over %zu stands, expected <= 1e-9", worst, stands);
    ASSERT_EXACT(worst, 0.0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_lone_tree_reaches_its_target_exactly),
        cmocka_unit_test(test_coupling_off_equals_the_targets),
        cmocka_unit_test(test_two_trees_meet_between_their_stems),
        cmocka_unit_test(test_taller_tree_claims_more_of_the_contested_space),
        cmocka_unit_test(test_no_overlap_at_every_spacing_and_dieback),
        cmocka_unit_test(test_beta_zero_leaves_gaps_within_one_step),
        cmocka_unit_test(test_growth_is_bit_identical_on_repeat),
        cmocka_unit_test(test_perturbation_keeps_hbar_and_moves_neighbours),
        cmocka_unit_test(test_self_check_measures_a_known_overlap),
        cmocka_unit_test(test_stems_closer_than_the_starting_crowns_are_unbuildable),
        cmocka_unit_test(test_frozen_output_marks_contact_sectors_only),
        cmocka_unit_test(test_bad_parameters_are_rejected),
        cmocka_unit_test(test_mutual_abrasion_both_sectors_die_back_by_beta_of_their_own_length),
        cmocka_unit_test(test_one_sided_switch_keeps_the_one_sided_rule),
        cmocka_unit_test(test_neighbour_dieback_abrades_the_contact_arc_of_both_crowns),
        cmocka_unit_test(test_target_dieback_removes_beta_of_the_target_length),
        cmocka_unit_test(test_start_fraction_sets_the_starting_crowns),
        cmocka_unit_test(test_dieback_readings_never_overlap_on_full_stands),
        cmocka_unit_test(test_mutual_abrasion_never_overlaps_on_full_stands),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
