# crownshy — build, tests, verification and the full reproduction.
# `make verify` (main job) and `make check` (tests) install missing Debian
# packages themselves when run as root; otherwise they print the apt-get line.
# Sources are discovered: src/ has one folder per stage of the pipeline
# (base -> forest, model -> exp, claims -> agree -> audit -> cli); every .c
# under them except src/cli/ is library code, every tests/test_*.c is one
# cmocka binary.
# Headers are included by name ("teacher.h"), with one -I per stage, so a
# pinned source's bytes do not depend on where its stage folder is.

SHELL := /bin/bash
CC ?= cc
# Determinism (design.md §1): no FMA contraction, no fast-math, no -march=native.
# -Wno-psabi: GCC notes that 32-byte vectors are passed differently since GCC
# 4.6 for nn.c's always-inlined helpers, which never cross a call boundary; the
# note ignores nn.c's pragma and would print on every build.
# -Wno-missing-field-initializers: option tables name the leading fields of
# opt_spec and leave the optional ones (required, choices) zero.
# Debug information (-g) only in the sanitizer build, where the reports need
# lines: it changes no instruction of an object (objdump -d is the same) and
# costs a third of the compile time of `make verify` from clean. DEBUG=1 adds it.
CFLAGS ?= -std=c11 -O2 -ffp-contract=off $(if $(DEBUG),-g) -Wall -Wextra -Wno-unused-parameter -Wno-psabi -Wno-missing-field-initializers \
          -D_POSIX_C_SOURCE=200809L -D_DEFAULT_SOURCE
STAGES := base forest model exp claims agree audit
CPPFLAGS += $(addprefix -Isrc/,$(STAGES) cli)
LDLIBS := -lgsl -lopenblas -lm
SANFLAGS := -g -fsanitize=address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=undefined

DEB_PKGS := libgsl-dev libopenblas-dev libcmocka-dev gnuplot-nox fonts-dejavu-core texlive-latex-base texlive-latex-recommended poppler-utils universal-ctags
SCALE ?= full
export OPENBLAS_NUM_THREADS := 1

B := build
LIB_SRC := $(foreach s,$(STAGES),$(wildcard src/$(s)/*.c))
LIB_HDR := $(foreach s,$(STAGES) cli,$(wildcard src/$(s)/*.h src/$(s)/*.inc))
LIB_OBJ := $(patsubst src/%.c,$(B)/obj/%.o,$(LIB_SRC))
ASAN_OBJ := $(patsubst src/%.c,$(B)/asan/obj/%.o,$(LIB_SRC))
TEST_SRC := $(wildcard tests/test_*.c)
TESTS := $(patsubst tests/%.c,$(B)/tests/%,$(TEST_SRC))
ASAN_TESTS := $(patsubst tests/%.c,$(B)/asan/tests/%,$(TEST_SRC))
CLI := $(B)/crownshy
# The step split of `make bench` (tests/bench/step_split.c): the library as
# every unit links it, with its four gemm entry points wrapped to time them.
SPLIT := $(B)/bench/step_split

.PHONY: all deps check check-fast verify verify-deep bench reproduce freeze figures paper deps-paper audit numbers trace fuzz clean dist dist-version
.DELETE_ON_ERROR:

all: $(CLI) $(TESTS) $(SPLIT)

# ---- dependencies -----------------------------------------------------------
deps:
	@missing=""; for p in $(DEB_PKGS); do \
	  dpkg-query -W -f='$${Status}' $$p 2>/dev/null | grep -q 'install ok installed' || missing="$$missing $$p"; \
	done; \
	if [ -z "$$missing" ]; then exit 0; fi; \
	if [ "$$(id -u)" = 0 ]; then \
	  echo "deps: installing$$missing"; \
	  export DEBIAN_FRONTEND=noninteractive; \
	  apt-get update -q >/dev/null && apt-get install -y -q --no-install-recommends$$missing >/dev/null || \
	    { echo "deps: apt-get install failed for$$missing" >&2; exit 1; }; \
	else \
	  echo "deps: missing Debian packages:$$missing" >&2; \
	  echo "deps: run: sudo apt-get install -y$$missing" >&2; exit 1; \
	fi

# ---- build ------------------------------------------------------------------
# The registry's computing functions (src/claims/claims.c includes the list):
# every `cs_status claim_*(const claim_row *row, claim_result *res)` defined
# in src/claims/, so a new claim function is listed by being written.
CLAIMS_LIST := $(B)/gen/claims_list.h
CPPFLAGS += -I$(B)/gen
$(CLAIMS_LIST): $(wildcard src/claims/*.c)
	@mkdir -p $(dir $@)
	@sed -nE 's/^cs_status (claim_[a-z0-9_]+)\(const claim_row \*row, claim_result \*res\)( *\{.*)?$$/X(\1)/p' \
	  $(sort $^) > $@.tmp && mv $@.tmp $@
$(B)/obj/claims/claims.o $(B)/asan/obj/claims/claims.o: $(CLAIMS_LIST)

$(B)/obj/%.o: src/%.c $(LIB_HDR)
	@mkdir -p $(dir $@)
	$(CC) $(CPPFLAGS) $(CFLAGS) -c $< -o $@
$(B)/asan/obj/%.o: src/%.c $(LIB_HDR)
	@mkdir -p $(dir $@)
	$(CC) $(CPPFLAGS) $(CFLAGS) $(SANFLAGS) -c $< -o $@
$(B)/libcrownshy.a: $(LIB_OBJ)
	rm -f $@; ar rcs $@ $^
$(B)/asan/libcrownshy.a: $(ASAN_OBJ)
	rm -f $@; ar rcs $@ $^
# The CLI's command handlers are a library of their own (tests call them);
# src/cli/main.c is the executable's one-line main.
CLI_LIB_SRC := $(filter-out src/cli/main.c,$(wildcard src/cli/*.c))
CLI_OBJ := $(patsubst src/%.c,$(B)/obj/%.o,$(CLI_LIB_SRC))
ASAN_CLI_OBJ := $(patsubst src/%.c,$(B)/asan/obj/%.o,$(CLI_LIB_SRC))
LIBS := $(B)/libcli.a $(B)/libcrownshy.a
ASAN_LIBS := $(B)/asan/libcli.a $(B)/asan/libcrownshy.a
$(B)/libcli.a: $(CLI_OBJ)
	rm -f $@; ar rcs $@ $^
$(B)/asan/libcli.a: $(ASAN_CLI_OBJ)
	rm -f $@; ar rcs $@ $^
$(CLI): src/cli/main.c $(LIBS)
	$(CC) $(CPPFLAGS) $(CFLAGS) $< $(LIBS) $(LDLIBS) -o $@
$(B)/tests/%: tests/%.c $(LIBS) $(wildcard tests/*.h) | $(B)/tests
	$(CC) $(CPPFLAGS) -Itests $(CFLAGS) $< $(LIBS) -lcmocka $(LDLIBS) -o $@
$(B)/asan/tests/%: tests/%.c $(ASAN_LIBS) $(wildcard tests/*.h) | $(B)/asan/tests
	$(CC) $(CPPFLAGS) -Itests $(CFLAGS) $(SANFLAGS) $< $(ASAN_LIBS) -lcmocka $(LDLIBS) -o $@
$(B)/tests $(B)/asan/tests:
	mkdir -p $@
SPLIT_WRAP := -Wl,--wrap=gemm_fma,--wrap=gemm_fma_epi,--wrap=gemm_fma_bias_epi,--wrap=gemm_fma_heads
$(SPLIT): tests/bench/step_split.c $(B)/libcrownshy.a
	@mkdir -p $(dir $@)
	$(CC) $(CPPFLAGS) $(CFLAGS) $< $(B)/libcrownshy.a $(SPLIT_WRAP) $(LDLIBS) -o $@

# ---- tests ------------------------------------------------------------------
# Every cmocka binary, then all of them again under ASan+UBSan; one aggregate
# line. Built on both cores unless make already runs parallel.
check: deps
	@$(MAKE) --no-print-directory $(if $(filter -j%,$(MAKEFLAGS)),,-j2) $(CLI) $(TESTS) $(ASAN_TESTS) $(SPLIT)
	@bash tests/run.sh $(TESTS) tests/tamper.sh tests/layout.sh tests/walls.sh tests/deep.sh tests/manifest.sh tests/citation.sh tests/paper_deps.sh tests/fonts.sh tests/spot.sh tests/docs.sh tests/readings_full.sh -- $(ASAN_TESTS)

# One claim's test alone, by its macro: make test-claim MACRO=MainRel
.PHONY: test-claim
test-claim: deps
	@test -n "$(MACRO)" || { echo "make test-claim: give MACRO=<claim macro>, e.g. MACRO=MainRel" >&2; exit 2; }
	@$(MAKE) --no-print-directory $(B)/tests/test_claims
	@$(B)/tests/test_claims '$(MACRO)' 2>&1

check-fast: deps
	@$(MAKE) --no-print-directory $(CLI) $(TESTS)
	@bash tests/run.sh $(TESTS) tests/layout.sh tests/citation.sh

# ---- verification (the reviewer's job) --------------------------------------
# Tier 1 (design.md §9): exit 0 when the package is consistent (a failing
# preregistered gate is a finding, reported "not reproduced"); STRICT=1 also
# fails on a failing gate.
# GNU make itself exits 2 whenever a recipe fails; the recipe ends with
# crownshy's own status (make prints it as "Error K") after one line naming its
# kind: 1 inconsistency, 2 usage, 3 bad input, 4 environment (design.md §11).
CS_STATUS = st=$$?; if [ $$st -ne 0 ]; then case $$st in 1) k=inconsistency;; 2) k=usage;; 3) k='bad input';; 4) k=environment;; *) k=other;; esac; \
  echo "make $@: crownshy exited $$st ($$k)" >&2; fi; exit $$st
# From clean the CLI is built on both cores unless make already runs parallel.
verify: deps
	@$(MAKE) --no-print-directory $(if $(filter -j%,$(MAKEFLAGS)),,-j2) $(CLI)
	@$(CLI) verify $(if $(STRICT),--strict) $(if $(SEED),--seed $(SEED)) $(if $(PREREG),--prereg $(PREREG)); $(CS_STATUS)

# Tier 2 (design.md §9): rerun every unit of each experiment whose manifest
# row says "rerun" (src/base/manifest.h; DEEP_UNITS is generated) into
# build/deep/ and compare with frozen/ bit for bit (data rows), with
# progress; then redraw every frozen model's samples from its weights.
DEEP := $(B)/deep
.PHONY: verify-deep
verify-deep: deps
	@$(MAKE) --no-print-directory $(CLI)
	@DEEP='$(DEEP)' JOBS=2 READING_NSEEDS='$(READING_NSEEDS)' CLI='$(CLI)' MAKE='$(MAKE)' DEEP_UNITS='$(patsubst $(RESULTS)/%,$(DEEP)/%,$(DEEP_UNITS))' bash src/exp/verify_deep.sh

audit: deps
	@$(MAKE) --no-print-directory $(CLI)
	@$(CLI) audit; $(CS_STATUS)

figures: deps
	@$(MAKE) --no-print-directory $(CLI)
	@$(CLI) figures

# Speed (design.md §10), measured here and never by a timed test: teacher CPU ms
# per 144-tree stand at N = 48 and 384; on every vector path of the CPU, the
# core's FMA peak and, as fractions of it measured beside each, the own product,
# sgemm, training and sampling of the plain and pair models, every goal judged,
# and the projected wall time of E3+E4 (README "Speed"); then where a training
# step's time goes (tests/bench/step_split.c, design.md §10.1); last the whole
# study's cost at full and at smoke scale (src/exp/study_cost.sh), the model
# units also at this core's rates (each unit's recipe run with --cost).
bench: deps
	@$(MAKE) --no-print-directory $(CLI) $(SPLIT)
	@$(CLI) bench-teacher
	@$(CLI) bench-model
	@$(SPLIT)
	@SMOKE_ROOT=$(B)/smoke SMOKE_STATE=$(B)/reproduce/smoke bash src/exp/study_cost.sh

numbers: deps
	@$(MAKE) --no-print-directory $(CLI)
	@$(CLI) numbers; $(CS_STATUS)

# ---- the full run of the study ----------------------------------------------
# One make target per unit (seed, arm, experiment) writing into $(RESULTS);
# `make -j2 reproduce` uses both cores, and an interrupted run resumes because
# finished units are files that make sees as up to date (written atomically).
# SCALE=smoke runs the whole pipeline at toy size into build/smoke/ (never frozen).
ifeq ($(SCALE),smoke)
RESULTS := $(B)/smoke
else
RESULTS := $(B)/results
endif
REPRODUCE_UNITS :=
DEEP_UNITS :=
MANIFEST_EXPERIMENTS :=
-include src/exp/experiments.mk

# ==== reproduce engines (design.md §13) ==========================================
# make reproduce [ENGINE=local|slurm] [SCALE=smoke] [SLURM_ARGS='sbatch options']
# make reproduce-status    per unit: done, queued, running, failed (with its log), missing
# make reproduce-graph     each unit and the units it needs
# src/exp/reproduce.sh reads the unit graph back from make (`make -pn` on REPRODUCE_UNITS),
# so the pipeline stays defined once, above. ENGINE=local runs make on the units with a
# progress line (units done of total, ETA from recorded wall times); ENGINE=slurm
# submits one job per unit not up to date, each running `make <unit>` like a local run,
# with --dependency=afterok on the jobs making its inputs. Bookkeeping (job ids, logs,
# wall times) in $(B)/reproduce/<results dir name>/.
ENGINE ?= local
SLURM_ARGS ?=
REPRODUCE_SH := src/exp/reproduce.sh
REPRODUCE_ENV = REPRODUCE_RESULTS='$(RESULTS)' REPRODUCE_UNITS='$(strip $(REPRODUCE_UNITS))' \
  REPRODUCE_STATE='$(B)/reproduce/$(notdir $(RESULTS))' REPRODUCE_CLI='$(CLI)' SCALE='$(SCALE)' \
  REPRODUCE_VARS='SCALE=$(SCALE)$(if $(filter command line,$(origin B)), B=$(B))$(if $(filter command line,$(origin RESULTS)), RESULTS=$(RESULTS))' \
  SLURM_ARGS='$(SLURM_ARGS)' MAKE='$(MAKE)'
.PHONY: reproduce-status reproduce-graph
# One reproduce at a time per tree: the second refuses (exit 4, naming the
# holder) instead of racing the first for the same results (build/reproduce.lock,
# held by the recipe's shell and its children until the run ends).
REPRODUCE_LOCK := build/reproduce.lock
reproduce: deps
	@mkdir -p $(dir $(REPRODUCE_LOCK)); exec 9>>$(REPRODUCE_LOCK); \
	 if ! flock -n 9; then echo "reproduce: another make reproduce is running in this tree ($(REPRODUCE_LOCK) held by pid $$(cat $(REPRODUCE_LOCK).pid 2>/dev/null || echo '?')): wait for it to end, or stop it" >&2; exit 4; fi; \
	 echo $$$$ > $(REPRODUCE_LOCK).pid; \
	 $(MAKE) --no-print-directory $(CLI) || exit $$?; \
	 if [ -z "$(strip $(REPRODUCE_UNITS))" ]; then echo "reproduce: no experiment registered yet"; \
	 else $(REPRODUCE_ENV) bash $(REPRODUCE_SH) $(ENGINE); fi
reproduce-status:
	@$(REPRODUCE_ENV) bash $(REPRODUCE_SH) status
reproduce-graph:
	@$(REPRODUCE_ENV) bash $(REPRODUCE_SH) graph
# the experiments and units the manifest gives make (src/base/manifest.h)
.PHONY: units
units:
	@echo "experiments: $(strip $(MANIFEST_EXPERIMENTS))"
	@echo "reproduce: $(strip $(REPRODUCE_UNITS))"
	@echo "verify-deep: $(strip $(DEEP_UNITS))"
# ==== end of reproduce engines ==============================================

# Copy finished full-scale results (tables, and the E3/E4 weights files) into
# frozen/, record their hashes and regenerate paper/numbers.tex. Smoke results are never frozen.
freeze: deps
	@$(MAKE) --no-print-directory $(CLI)
	@if [ "$(SCALE)" = smoke ]; then echo "freeze: smoke results are never frozen" >&2; exit 2; fi
	@if [ -d $(B)/results ]; then \
	  for d in $(B)/results/*/; do [ -d "$$d" ] || continue; e=$$(basename $$d); mkdir -p frozen/$$e; \
	    (cd $$d && find . \( -name '*.tsv' -o -name 'weights_*.ckpt' \) ! -name '*.tmp*' ! -name '.*' ! -path './*/*/figure_crowns*' ! -path './*/*/figure_poly*' -exec cp --parents {} $(CURDIR)/frozen/$$e/ \;) ; done; fi
	@# the readings and the sensitivity units keep their run folders; their figure tables are not part of their tables;
	@# a summary is remade only when units of its experiment were frozen now (freezing one experiment touches no other)
	@if [ -d $(B)/results/readings ] && [ -f frozen/readings/summary.tsv ]; then $(CLI) readings-summary --dir frozen/readings --out frozen/readings/summary.tsv >/dev/null; fi
	@if [ -d $(B)/results/sensitivity ] && [ -f frozen/sensitivity/summary.tsv ]; then $(CLI) sensitivity-summary --dir frozen/sensitivity --out frozen/sensitivity/summary.tsv >/dev/null; fi
	@$(CLI) hash-frozen
	@$(CLI) numbers

trace: $(CLI)
	@$(CLI) trace $(MACRO)

# ---- the release archive ------------------------------------------------------
# `make dist`: $(B)/dist/crownshy-VERSION.tar.gz (VERSION from CITATION.cff) with
# its SHA-256 (printed, and in crownshy-VERSION.tar.gz.sha256). It holds the committed and new unignored files of the package
# (git ls-files; without .git, the same folders less the ignored build outputs)
# and no build/. Byte-reproducible for one tree: names sorted, owner 0, every
# mtime the last commit's time (or SOURCE_DATE_EPOCH), gzip without a timestamp.
# tests/dist.sh unpacks it without .git and runs `make verify` there.
VERSION := $(shell sed -n 's/^version: *//p' CITATION.cff 2>/dev/null)
DIST := crownshy-$(VERSION)
DIST_PATHS := Makefile README.md LICENSE CITATION.cff .ci .gitignore src tests gates frozen audit paper figures
dist-version:
	@echo '$(VERSION)'
dist:
	@[ -n '$(VERSION)' ] || { echo "dist: no 'version:' line in CITATION.cff" >&2; exit 1; }
	@mkdir -p $(B)/dist
	@set -eo pipefail; \
	if [ -e .git ]; then git ls-files -co --exclude-standard -- $(DIST_PATHS); \
	else find $(DIST_PATHS) -type f ! -name '*.tmp*' ! -name '*.pdf' ! -path 'paper/*.aux' ! -path 'paper/*.log' ! -path 'paper/*.out'; fi \
	  | LC_ALL=C sort -u > $(B)/dist/files; \
	if [ -e .git ] && [ -n "$$(git status --porcelain -- $(DIST_PATHS))" ]; then echo "dist: note: uncommitted changes are included"; fi; \
	epoch=$${SOURCE_DATE_EPOCH:-$$(git log -1 --format=%ct 2>/dev/null || echo 0)}; \
	tar --transform 's,^,$(DIST)/,' --sort=name --owner=0 --group=0 --numeric-owner --mtime=@$$epoch \
	  --no-recursion -T $(B)/dist/files -cf - | gzip -9n > $(B)/dist/$(DIST).tar.gz.tmp; \
	mv $(B)/dist/$(DIST).tar.gz.tmp $(B)/dist/$(DIST).tar.gz; \
	echo "dist: $(B)/dist/$(DIST).tar.gz ($$(wc -l < $(B)/dist/files) files, $$(du -h $(B)/dist/$(DIST).tar.gz | cut -f1))"; \
	(cd $(B)/dist && sha256sum $(DIST).tar.gz | tee $(DIST).tar.gz.sha256)

# ---- the write-up -------------------------------------------------------------
# pdflatex and every package paper/main.tex loads: installed as root, else named (src/cli/paper_deps.sh)
deps-paper:
	@bash src/cli/paper_deps.sh paper/main.tex

paper: $(CLI) deps-paper
	@$(CLI) figures >/dev/null || { echo "paper: a figure failed to draw (make figures)" >&2; exit 1; }
	@$(CLI) numbers --check >/dev/null || { echo "paper: paper/numbers.tex is stale; run make numbers" >&2; exit 1; }
	@cd paper && for pass in 1 2; do \
	  pdflatex -interaction=nonstopmode -halt-on-error main.tex >/dev/null || { \
	    echo "paper: pdflatex failed (paper/main.log):" >&2; grep -A3 '^!' main.log | head -12 >&2; exit 1; }; done; \
	if grep -q 'Float too large\|^Overfull' main.log; then \
	  echo "paper: paper/main.pdf overflows its page (paper/main.log):" >&2; grep 'Float too large\|^Overfull' main.log >&2; exit 1; fi; \
	echo "paper: wrote paper/main.pdf (no float or line overflows its page)"

# ---- fuzzing (design.md §11): libFuzzer on the parsers, FUZZ_SECONDS each ---------
# Needs clang with libFuzzer (Debian: clang, libclang-rt-14-dev); built with -DNN_NO_CLONES
# (clang refuses nn.c's AVX-512 clones; the parsers do not need them). Seeds: the
# committed frozen tables, gates, numbers.tex and a fresh smoke checkpoint.
# A crash leaves its input in build/fuzz/<target>/crash-*; copy it into
# tests/data/fuzz/ and add a regression case to the parser's cmocka tests.
FUZZ_SECONDS ?= 60
FUZZ_TARGETS := tsv gate ckpt numbers gatemap aggr paper
FUZZ_CC := clang
FUZZ_FLAGS := -g -O1 -fsanitize=fuzzer,address,undefined -DNN_NO_CLONES $(addprefix -Isrc/,$(STAGES)) -Itests/fuzz -D_POSIX_C_SOURCE=200809L -D_DEFAULT_SOURCE
$(B)/fuzz/fuzz_%: tests/fuzz/fuzz_%.c $(LIB_SRC) $(LIB_HDR) tests/fuzz/fuzz_common.h
	@mkdir -p $(dir $@)
	$(FUZZ_CC) $(FUZZ_FLAGS) $< $(LIB_SRC) $(LDLIBS) -o $@
fuzz: $(addprefix $(B)/fuzz/fuzz_,$(FUZZ_TARGETS))
	@command -v $(FUZZ_CC) >/dev/null || { echo "fuzz: clang not installed (apt-get install clang libclang-rt-14-dev)" >&2; exit 1; }
	@for t in tsv gate ckpt numbers gatemap aggr paper; do mkdir -p $(B)/fuzz/$$t/corpus; done
	@cp frozen/*/*.tsv audit/claims.tsv $(B)/fuzz/tsv/corpus/ 2>/dev/null; cp gates/*.gate $(B)/fuzz/gate/corpus/
	@cp paper/numbers.tex $(B)/fuzz/numbers/corpus/
	@cp audit/gate_map.tsv $(B)/fuzz/gatemap/corpus/; cp audit/aggregates.tsv $(B)/fuzz/aggr/corpus/; cp paper/*.tex $(B)/fuzz/paper/corpus/
	@ls $(B)/ckpt/smoke/*.ckpt >/dev/null 2>&1 && cp $(B)/ckpt/smoke/*.ckpt $(B)/fuzz/ckpt/corpus/ || true
	@for t in $(FUZZ_TARGETS); do \
	  echo "fuzz: $$t for $(FUZZ_SECONDS) s"; \
	  (cd $(B)/fuzz/$$t && ../fuzz_$$t -max_total_time=$(FUZZ_SECONDS) -max_len=65536 -print_final_stats=1 corpus > log 2>&1); rc=$$?; \
	  grep -E "stat::number_of_executed_units|Done" $(B)/fuzz/$$t/log | tail -1; \
	  if [ $$rc -ne 0 ]; then echo "fuzz: $$t FOUND A CRASH (build/fuzz/$$t/log)"; exit 1; fi; done

clean:
	rm -rf $(B)
