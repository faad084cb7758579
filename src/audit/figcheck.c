/* figcheck: a figure's plotted data and its renderer; see figcheck.h. */
#include "figcheck.h"
#include "afile.h"
#include "audit_data.h"
#include "paths.h"
#include "prov.h"
#include "sha256.h"
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

/* The Debian packages whose versions decide a PNG's bytes beside the data. */
static const char *const RENDER_DEBS[] = {"gnuplot-nox",
                                          "libcairo2",
                                          "libpango-1.0-0",
                                          "libpangocairo-1.0-0",
                                          "libfreetype6",
                                          "libfontconfig1",
                                          "libpixman-1-0",
                                          "libpng16-16",
                                          "zlib1g",
                                          "fonts-dejavu-core",
                                          NULL};

/* The SHA-256 of everything cmd prints. */
static void output_sha(const char *cmd, char hex[65])
{
    sha256_ctx c;
    uint8_t d[32];
    sha256_init(&c);
    FILE *p = popen(cmd, "r");
    if (p) {
        char buf[4096];
        size_t k;
        while ((k = fread(buf, 1, sizeof buf, p)) > 0) sha256_update(&c, buf, k);
        pclose(p);
    }
    sha256_final(&c, d);
    sha256_tohex(d, hex);
}

cs_status figcheck_renderer(char *buf, size_t n)
{
    size_t o = 0;
    char line[512], cmd[256];
#define ADD(...)                                                                                                       \
    do {                                                                                                               \
        int w_ = snprintf(buf + o, n - o, __VA_ARGS__);                                                                \
        if (w_ < 0 || (size_t)w_ >= n - o) return cs_err(CS_EINPUT, "figcheck: renderer text too long");               \
        o += (size_t)w_;                                                                                               \
    } while (0)
    audit_run_line("gnuplot --version 2>/dev/null", line, sizeof line);
    ADD("gnuplot\t%s\n", line[0] ? line : "absent");
    for (size_t i = 0; RENDER_DEBS[i]; i++) {
        snprintf(cmd, sizeof cmd, "dpkg-query -W -f '${Version}' %s 2>/dev/null", RENDER_DEBS[i]);
        audit_run_line(cmd, line, sizeof line);
        ADD("deb:%s\t%s\n", RENDER_DEBS[i], line[0] ? line : "absent");
    }
    audit_run_line("fc-match -f '%{file}' '" FIGCHECK_FONT "' 2>/dev/null", line, sizeof line);
    char hex[65] = "absent";
    if (!line[0] || prov_sha256_file(line, hex)) snprintf(hex, sizeof hex, "absent");
    ADD("font\t%s\n", line[0] ? line : "absent");
    ADD("font_sha256\t%s\n", hex);
    /* fontconfig's whole match (file, hinting, antialiasing, ...) for the font */
    output_sha("fc-match -v '" FIGCHECK_FONT "' 2>/dev/null", hex);
    ADD("fontconfig_match_sha256\t%s\n", hex);
#undef ADD
    return CS_OK;
}

/* The value of key in "key\tvalue\n" text, into out; 0 when absent. */
static int value_of(const char *text, const char *key, char *out, size_t n)
{
    const size_t kl = strlen(key);
    for (const char *l = text; l && *l; l = strchr(l, '\n') ? strchr(l, '\n') + 1 : NULL) {
        if (*l == '#' || strncmp(l, key, kl) || l[kl] != '\t') continue;
        const char *v = l + kl + 1;
        snprintf(out, n, "%.*s", (int)strcspn(v, "\n"), v);
        return 1;
    }
    return 0;
}

cs_status figcheck_renderer_compare(const char *pinned_path, const char *now, int *same, char *diff, size_t n)
{
    *same = 0;
    diff[0] = '\0';
    char *pinned = afile_read(pinned_path);
    if (!pinned) { snprintf(diff, n, "%s missing (make figures writes it)", pinned_path); return CS_OK; }
    size_t o = 0;
    int differ = 0;
    for (const char *l = now; *l; ) {
        const char *e = strchr(l, '\n');
        size_t ll = e ? (size_t)(e - l) : strlen(l);
        char key[96], here[512], was[512];
        const char *tab = memchr(l, '\t', ll);
        if (tab) {
            snprintf(key, sizeof key, "%.*s", (int)(tab - l), l);
            snprintf(here, sizeof here, "%.*s", (int)(ll - (size_t)(tab - l) - 1), tab + 1);
            if (!value_of(pinned, key, was, sizeof was)) snprintf(was, sizeof was, "(not pinned)");
            if (strcmp(was, here)) {
                differ = 1;
                if (o < n)
                    o += (size_t)snprintf(diff + o, n - o, "%s%s: pinned %s, here %s", o ? "; " : "", key, was, here);
            }
        }
        l += ll + (e != NULL);
    }
    free(pinned);
    *same = !differ;
    return CS_OK;
}

cs_status figcheck_table_sha(const char *tabfile, char hex[65])
{
    FILE *f = fopen(tabfile, "r");
    if (!f) return cs_err(CS_EIO, "%s: cannot read the plotted data", tabfile);
    sha256_ctx c;
    uint8_t d[32];
    sha256_init(&c);
    char line[4096];
    int mid = 0; /* inside an over-long line: its rest is data too */
    while (fgets(line, sizeof line, f)) {
        const int whole = strchr(line, '\n') != NULL;
        if (!mid && (line[0] == '#' || line[0] == '\n')) { mid = !whole; continue; }
        sha256_update(&c, line, strlen(line));
        mid = !whole;
    }
    int bad = ferror(f);
    fclose(f);
    if (bad) return cs_err(CS_EIO, "%s: read error", tabfile);
    sha256_final(&c, d);
    sha256_tohex(d, hex);
    return CS_OK;
}

cs_status figcheck_pinned_sha(const char *list, const char *stem, char hex[65], int *found)
{
    *found = 0;
    FILE *f = fopen(list, "r");
    if (!f) return CS_OK;
    char line[512];
    while (fgets(line, sizeof line, f)) {
        line[strcspn(line, "\n")] = '\0';
        if (line[0] == '#' || strlen(line) < 67 || line[64] != ' ' || line[65] != ' ') continue;
        if (strcmp(line + 66, stem)) continue;
        snprintf(hex, 65, "%.64s", line);
        *found = 1;
    }
    fclose(f);
    return CS_OK;
}

void figcheck_table_cmd(const char *script, const char *scratch, const char *tabfile, const char *log, char *cmd,
                        size_t n)
{
    snprintf(cmd, n, "gnuplot -e \"outdir='%s'; set table '%s'\" '%s' > '%s' 2>&1", scratch, tabfile, script, log);
}

cs_status figcheck_write(const char *renderer_path, const char *renderer, const char *plotted_path,
                         const char *const *stems, const char (*hexes)[65], size_t nfig)
{
    afile a;
    cs_status st = afile_open(&a, renderer_path);
    if (st) return st;
    if (fprintf(a.f,
                "# what: the renderer the committed PNGs were drawn with (src/audit/figcheck.h); verify compares the "
                "raster only where it is the same\n"
                "# written by: crownshy figures\n%s",
                renderer) < 0)
        a.err = 1;
    if ((st = afile_commit(&a))) return st;
    if ((st = afile_open(&a, plotted_path))) return st;
    if (fprintf(a.f, "# what: SHA-256 of each figure's plotted data (gnuplot `set table`, comment and blank lines left "
                     "out; src/audit/figcheck.h)\n"
                     "# written by: crownshy figures; verify compares it on any renderer\n") < 0)
        a.err = 1;
    for (size_t i = 0; i < nfig; i++) if (fprintf(a.f, "%s  %s\n", hexes[i], stems[i]) < 0) a.err = 1;
    return afile_commit(&a);
}

static int has_gnuplot(void)
{
    return system("command -v gnuplot >/dev/null 2>&1") == 0;
}

/* Byte-compare two files: 0 equal, 1 differ, -1 a is unreadable, -2 b is. */
static int same_bytes(const char *a, const char *b)
{
    FILE *fa = fopen(a, "rb"), *fb = fopen(b, "rb");
    int r = !fa ? -1 : !fb ? -2 : 0;
    char ba[65536], bb[65536];
    while (!r) {
        size_t na = fread(ba, 1, sizeof ba, fa), nb = fread(bb, 1, sizeof bb, fb);
        if (na != nb || memcmp(ba, bb, na)) r = 1;
        else if (na == 0) break;
    }
    if (fa) fclose(fa);
    if (fb) fclose(fb);
    return r;
}

/* Copy src over dst atomically (temp beside dst, then rename). */
static cs_status install_file(const char *src, const char *dst)
{
    afile a;
    cs_status st = afile_open(&a, dst);
    if (st) return st;
    FILE *f = fopen(src, "rb");
    if (!f) { afile_abort(&a); return cs_err(CS_EIO, "%s: cannot read", src); }
    char buf[65536];
    size_t n;
    while ((n = fread(buf, 1, sizeof buf, f)) > 0) if (fwrite(buf, 1, n, a.f) != n) a.err = 1;
    fclose(f);
    return afile_commit(&a);
}

/* verify draws the figures while it audits: every script's gnuplot is started
 * in the background, two at a time, into build/figures.<pid>/ (status in
 * <script>.rc); figcheck_verify then waits and compares. */
static pid_t g_fig_pid = -1;

static void figures_outdir(char *buf, size_t n)
{
    snprintf(buf, n, "build/figures.%ld", (long)getpid());
}

/* The command that writes script's plotted data into <outdir>/<base>.tab (its
 * terminal output into <outdir>/tab/, apart from the redraws). */
static void table_cmd(const char *script, const char *outdir, char *cmd, size_t n)
{
    const char *base = script + strlen(PATHS_FIGURES_DIR) + 1;
    char scratch[200], tab[400], log[400];
    snprintf(scratch, sizeof scratch, "%s/tab", outdir);
    snprintf(tab, sizeof tab, "%s/%s.tab", outdir, base);
    snprintf(log, sizeof log, "%s/%s.tab.log", outdir, base);
    figcheck_table_cmd(script, scratch, tab, log, cmd, n);
}

void figcheck_launch(void)
{
    char outdir[128], jobs[200], cmd[400];
    figures_outdir(outdir, sizeof outdir);
    if (afile_mkdir_parents(outdir) || (mkdir(outdir, 0777) && errno != EEXIST) || !has_gnuplot()) return;
    char scratch[200];
    snprintf(scratch, sizeof scratch, "%s/tab", outdir);
    if (mkdir(scratch, 0777) && errno != EEXIST) return;
    paths_list gps;
    if (paths_list_files(PATHS_FIGURES_DIR, ".gp", 0, &gps)) return;
    /* one shell line per script; xargs runs two at a time */
    snprintf(jobs, sizeof jobs, "%s/jobs", outdir);
    FILE *f = fopen(jobs, "w");
    for (size_t i = 0; f && i < gps.n; i++) {
        const char *base = gps.p[i] + strlen(PATHS_FIGURES_DIR) + 1;
        fprintf(f, "gnuplot -e \"outdir='%s'\" '%s' > '%s/%s.log' 2>&1; echo $? > '%s/%s.rc'\n", outdir, gps.p[i],
                outdir, base, outdir, base);
        char tcmd[1400];
        table_cmd(gps.p[i], outdir, tcmd, sizeof tcmd);
        fprintf(f, "%s; echo $? > '%s/%s.tab.rc'\n", tcmd, outdir, base);
    }
    paths_list_free(&gps);
    if (!f || fclose(f)) return;
    snprintf(cmd, sizeof cmd, "xargs -P 2 -d '\\n' -I{} sh -c {} < '%s'", jobs);
    fflush(stdout);
    pid_t pid = fork();
    if (pid == 0) {
        execl("/bin/sh", "sh", "-c", cmd, (char *)NULL);
        _exit(127);
    }
    g_fig_pid = pid;
}

/* The launched redraw of one script: its exit status, or -1 when not launched. */
static int launched_status(const char *outdir, const char *base)
{
    if (g_fig_pid < 0) return -1;
    char p[400];
    snprintf(p, sizeof p, "%s/%s.rc", outdir, base);
    FILE *f = fopen(p, "r");
    int rc = 1;
    if (f) { if (fscanf(f, "%d", &rc) != 1) rc = 1; fclose(f); }
    return rc;
}

void figcheck_wait(void)
{
    if (g_fig_pid <= 0) return;
    int ws;
    while (waitpid(g_fig_pid, &ws, 0) < 0 && errno == EINTR) {}
}

/* Read a figure script's "# data: path" lines (its registered inputs: a
 * missing one is a failure), the stem of the PNG it writes, and the claims
 * the inputs feed. */
static void script_inputs(const char *script, const claims *c, char *stem, size_t sn, char *feeds, size_t fn,
                          char *missing, size_t mn)
{
    FILE *f = fopen(script, "r");
    char line[1024];
    size_t fo = 0;
    feeds[0] = missing[0] = '\0';
    while (f && fgets(line, sizeof line, f)) {
        char *o = strstr(line, "set output outdir.'/");
        if (o && strstr(o, ".png'")) snprintf(stem, sn, "%.*s", (int)(strstr(o, ".png'") - o - 20), o + 20);
        if (strncmp(line, "# data: ", 8)) continue;
        line[strcspn(line, "\n")] = '\0';
        struct stat sb;
        /* a reading's unit set (design.md §8) may hold no unit yet: the
         * script draws the units frozen so far, and the redraw is compared */
        const int unit_set = strchr(line + 8, '*') && claims_awaited_source(line + 8);
        if (!unit_set && stat(line + 8, &sb) != 0 && !missing[0]) snprintf(missing, mn, "%s", line + 8);
        char one[600];
        if (c) audit_feeds(c, line + 8, one, sizeof one);
        if (c && strcmp(one, "(no claim)") && fo < fn - 2 && !strstr(feeds, one))
            fo += (size_t)snprintf(feeds + fo, fn - fo, "%s%s", fo ? "; " : "", one);
    }
    if (f) fclose(f);
    if (!feeds[0]) snprintf(feeds, fn, "(no claim)");
}

/* The SHA-256 of the data script plots (its `set table` run: launched, or run
 * now); -1 when gnuplot could not write it. */
static int plotted_sha(const char *script, const char *outdir, char hex[65])
{
    const char *base = script + strlen(PATHS_FIGURES_DIR) + 1;
    char tabbase[160], tab[400];
    snprintf(tabbase, sizeof tabbase, "%s.tab", base);
    snprintf(tab, sizeof tab, "%s/%s.tab", outdir, base);
    int trc = launched_status(outdir, tabbase);
    if (trc < 0) {
        char scratch[200], tcmd[1400];
        snprintf(scratch, sizeof scratch, "%s/tab", outdir);
        if (mkdir(scratch, 0777) && errno != EEXIST) trc = 1;
        else { table_cmd(script, outdir, tcmd, sizeof tcmd); trc = system(tcmd); }
    }
    return trc != 0 || figcheck_table_sha(tab, hex) ? -1 : 0;
}

typedef struct { const char *outdir; int install, gp, rsame; const claims *c; } fig_run;

/* Install the redraw of one figure (PNG, and its PDF when drawn). */
static void figure_install(checklist *cl, const char *item, const char *script, const char *outdir, const char *stem,
                           const char *png)
{
    char drawn[300], pdf[300], pdfdst[300];
    snprintf(drawn, sizeof drawn, "%s/%s.png", outdir, stem);
    cs_status st = install_file(drawn, png);
    snprintf(pdf, sizeof pdf, "%s/%s.pdf", outdir, stem);
    snprintf(pdfdst, sizeof pdfdst, "%s/%s.pdf", PATHS_FIGURES_DIR, stem);
    struct stat sb;
    if (!st && stat(pdf, &sb) == 0) st = install_file(pdf, pdfdst);
    if (st) checklist_add(cl, VERDICT_FAIL, item, "%s", cs_errmsg());
    else checklist_add(cl, VERDICT_PASS, item, "redrawn by gnuplot %s into %s", script, png);
}

/* Compare the redraw of one figure with the committed PNG (only under the
 * pinned renderer). */
static void figure_compare(checklist *cl, const char *item, const char *script, const fig_run *r, const char *stem,
                           const char *png, const char *feeds)
{
    const char *base = script + strlen(PATHS_FIGURES_DIR) + 1;
    char drawn[300];
    snprintf(drawn, sizeof drawn, "%s/%s.png", r->outdir, stem);
    struct stat sb;
    int d = !r->rsame ? (stat(drawn, &sb) != 0 ? -1 : 2) : same_bytes(drawn, png);
    if (d == 2)
        checklist_add(cl, VERDICT_PASS, item, "the data %s plots equal %s; %s not compared (renderer differs)", script,
                      PATHS_FIG_PLOTTED, png);
    else if (d == 0)
        checklist_add(cl, VERDICT_PASS, item,
                      "%s redrawn by %s into %s: byte-identical, and the data it plots equal %s", png, script,
                      r->outdir, PATHS_FIG_PLOTTED);
    else if (d == -1)
        checklist_add(cl, VERDICT_FAIL, item, "%s drew no %s (see %s/%s.log); claims: %s", script, drawn, r->outdir,
                      base, feeds);
    else if (d == -2)
        checklist_add(cl, VERDICT_FAIL, item, "%s is missing (the committed figure; make figures draws it); claims: %s",
                      png, feeds);
    else
        checklist_add(
            cl, VERDICT_FAIL, item,
            "%s differs from its redraw by %s from frozen/ (%s): the figure or its script was changed; claims: %s", png,
            script, drawn, feeds);
}

/* One figure: its inputs, its redraw, the data it plots (into hex: 0), then
 * install or compare; -1 when its script or its table failed. */
static int figure_one(checklist *cl, const char *script, const fig_run *r, char hex[65])
{
    const char *base = script + strlen(PATHS_FIGURES_DIR) + 1;
    char item[128], stem[96], png[256], feeds[1200], missing[1100], fig[96];
    snprintf(stem, sizeof stem, "%.*s", (int)(strlen(base) - 3), base);
    snprintf(fig, sizeof fig, "%s", stem);
    snprintf(item, sizeof item, "figure %.90s", stem);
    script_inputs(script, r->c, stem, sizeof stem, feeds, sizeof feeds, missing, sizeof missing);
    snprintf(png, sizeof png, "%s/%s.png", PATHS_FIGURES_DIR, stem);
    if (missing[0]) {
        checklist_add(cl, VERDICT_FAIL, item, "%s needs %s, which is missing (a registered input); claims: %s", script,
                      missing, feeds);
        return -1;
    }
    if (!r->gp) { checklist_add(cl, VERDICT_FAIL, item, "gnuplot not installed (make deps)"); return -1; }
    char cmd[1400];
    snprintf(cmd, sizeof cmd, "gnuplot -e \"outdir='%s'\" '%s' > %s/%s.log 2>&1", r->outdir, script, r->outdir, base);
    int rc = launched_status(r->outdir, base);
    if (rc < 0) rc = system(cmd);
    if (rc != 0) {
        checklist_add(cl, VERDICT_FAIL, item, "gnuplot %s failed (see %s/%s.log); claims: %s", script, r->outdir, base,
                      feeds);
        return -1;
    }
    /* what the figure plots, apart from how it is drawn */
    if (plotted_sha(script, r->outdir, hex)) {
        checklist_add(cl, VERDICT_FAIL, item,
                      "gnuplot could not write the data %s plots (see %s/%s.tab.log); claims: %s", script, r->outdir,
                      base, feeds);
        return -1;
    }
    if (r->install) { figure_install(cl, item, script, r->outdir, stem, png); return 0; }
    char want[65];
    int found = 0;
    figcheck_pinned_sha(PATHS_FIG_PLOTTED, fig, want, &found);
    if (!found)
        checklist_add(cl, VERDICT_FAIL, item, "%s has no line for %s (make figures writes it); claims: %s",
                      PATHS_FIG_PLOTTED, fig, feeds);
    else if (strcmp(want, hex))
        checklist_add(cl, VERDICT_FAIL, item,
                      "the data %s plots (sha256 %.16s) differ from %s (%.16s): the script or an input it reads was "
                      "changed; claims: %s",
                      script, hex, PATHS_FIG_PLOTTED, want, feeds);
    else figure_compare(cl, item, script, r, stem, png, feeds);
    return 0;
}

/* The renderer here against figures/renderer.tsv (its text kept in buf); -1 on error. */
static int renderer_check(checklist *cl, int install, char *buf, size_t n, int *same)
{
    char rdiff[2048];
    if (figcheck_renderer(buf, n) || figcheck_renderer_compare(PATHS_FIG_RENDERER, buf, same, rdiff, sizeof rdiff)) {
        checklist_add(cl, VERDICT_FAIL, "figures renderer", "%s", cs_errmsg());
        return -1;
    }
    if (install) return 0;
    if (*same)
        checklist_add(cl, VERDICT_PASS, "figures renderer", "the renderer of %s: rasters compared byte for byte",
                      PATHS_FIG_RENDERER);
    else
        checklist_add(cl, VERDICT_PASS, "figures renderer",
                      "renderer differs: %s; rasters not compared, each figure's plotted data compared with %s (not an "
                      "inconsistency of the results)",
                      rdiff, PATHS_FIG_PLOTTED);
    return 0;
}

void figcheck_verify(checklist *cl, int install, const claims *c)
{
    figcheck_wait();
    paths_list gps;
    if (paths_list_files(PATHS_FIGURES_DIR, ".gp", 0, &gps)) {
        checklist_add(cl, VERDICT_FAIL, "figures", "%s", cs_errmsg());
        return;
    }
    /* every figure is drawn into build/ first: verify compares the redraw
     * with the committed PNG and never writes into figures/; `crownshy
     * figures` installs a redraw only when its script succeeded */
    char outdir[128], renderer[4096];
    figures_outdir(outdir, sizeof outdir);
    fig_run r = {outdir, install, has_gnuplot(), 0, c};
    char (*hexes)[65] = calloc(gps.n ? gps.n : 1, sizeof *hexes);
    char (*figs)[96] = calloc(gps.n ? gps.n : 1, sizeof *figs);
    const char **figp = calloc(gps.n ? gps.n : 1, sizeof *figp);
    size_t ntab = 0, tabfail = 0;
    if (!hexes || !figs || !figp) checklist_add(cl, VERDICT_FAIL, "figures", "out of memory");
    else if (afile_mkdir_parents(outdir) || (mkdir(outdir, 0777) && errno != EEXIST))
        checklist_add(cl, VERDICT_FAIL, "figures", "%s: cannot create: %s", outdir, strerror(errno));
    else if (!renderer_check(cl, install, renderer, sizeof renderer, &r.rsame)) {
        for (size_t i = 0; i < gps.n; i++) {
            if (figure_one(cl, gps.p[i], &r, hexes[ntab])) { tabfail++; continue; }
            const char *base = gps.p[i] + strlen(PATHS_FIGURES_DIR) + 1;
            snprintf(figs[ntab], sizeof figs[ntab], "%.*s", (int)(strlen(base) - 3), base);
            figp[ntab] = figs[ntab];
            ntab++;
        }
        if (install && !tabfail) {
            if (figcheck_write(PATHS_FIG_RENDERER, renderer, PATHS_FIG_PLOTTED, figp, (const char (*)[65])hexes, ntab))
                checklist_add(cl, VERDICT_FAIL, "figures", "%s", cs_errmsg());
            else
                checklist_add(cl, VERDICT_PASS, "figures", "wrote %s (%zu figures) and %s", PATHS_FIG_PLOTTED, ntab,
                              PATHS_FIG_RENDERER);
        } else if (install)
            checklist_add(cl, VERDICT_FAIL, "figures", "%s and %s left as they were: %zu script(s) failed",
                          PATHS_FIG_PLOTTED, PATHS_FIG_RENDERER, tabfail);
    }
    free(hexes); free(figs); free(figp);
    paths_list_free(&gps);
    /* keep the redraws only when something failed (to look at) */
    int failed = 0;
    for (size_t i = 0; i < cl->n; i++) failed |= cl->items[i].v == VERDICT_FAIL;
    if (!failed) {
        char cmd[200];
        snprintf(cmd, sizeof cmd, "rm -rf '%s'", outdir);
        if (system(cmd) != 0) { /* a leftover folder under build/ is harmless */ }
    }
}
