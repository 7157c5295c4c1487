/* ---- Judging coverage: glrefcheck's verdict, looked up ---- */
/* The rules are not written here. The case's data holds a verdict table, computed by glrefcheck
   with the comparator's own rules (compare::coverage_verdict) for every value of the edge bits,
   every kind of primitive GL may keep, every fragment count against the reference's and both
   outcomes of the fragment trace. This file says what GL did at a pixel in those terms and looks
   the label up. Needs CHANNELS (depth and every component). */

/* A pixel's coverage label (compare's CoverageStats::Label; NO_LABEL: GL agrees). */
enum label { NO_LABEL, EXACT_TIE, WITHIN_SNAPPING, GAP, DOUBLE_HIT, FILL_RULE };
/* What GL kept at a pixel (compare::CoverageObservation::Kept). */
enum kept { KEPT_REFERENCE, KEPT_CANDIDATE, KEPT_OTHER };
/* GL's fragment count against the reference's (compare::CoverageObservation::Count). */
enum count { COUNT_SAME, COUNT_FEWER, COUNT_MORE };
/* The verdict table's rows, one per value of the edge bits: the label by what GL kept, its
   count, and whether its fragment trace is one a conforming implementation may give (0, 1). */
typedef unsigned char verdict_row[3][3][2];

/* Another fragment that may win the depth test at a pixel: its primitive, depth and
   components, and their allowances. */
struct candidate {
  int pixel, primitive;
  float values[CHANNELS];
  double allowed[CHANNELS];
};
/* The fragment traces a conforming implementation may give at one pixel: traces[first ..
   first + count) of a trace_list. */
struct traced {
  int pixel, first, count;
};
struct trace_list {
  int pixel_count; /* sorted by pixel */
  const struct traced *pixels;
  const unsigned (*traces)[3]; /* fragments, sum of p + 1, sum of a hash of p */
};
/* What the reference has at a pixel. */
struct expected_coverage {
  int primitive; /* -1: none */
  unsigned fragments, edges;
};

/* The candidate of primitive p among `first`..`end` (one pixel's), or NULL. */
static const struct candidate *candidate_of(const struct candidate *first,
                                            const struct candidate *end, int p) {
  for (; first != end; ++first)
    if (first->primitive == p && p >= 0) return first;
  return NULL;
}

/* Whether GL's trace at pixel i (its fragment count; the sums of p + 1 and of a hash of p over
   its fragments, as floats) is one `list` admits there. 1: it is, or nothing is known (no list
   for the pixel, or sums that are not exact integers). */
static int trace_admitted(const struct trace_list *list, int i, unsigned gl_fragments,
                          const float *trace) {
  int lo = 0, hi = list->pixel_count, k;
  const float ids = trace[0], hashes = trace[1];
  while (lo < hi) {
    const int mid = lo + (hi - lo) / 2;
    if (list->pixels[mid].pixel < i) lo = mid + 1; else hi = mid;
  }
  if (lo == list->pixel_count || list->pixels[lo].pixel != i) return 1;
  if (!(ids >= 0 && ids < 16777216.0f && ids == floor(ids)) ||
      !(hashes >= 0 && hashes < 16777216.0f && hashes == floor(hashes)))
    return 1;
  for (k = list->pixels[lo].first; k < list->pixels[lo].first + list->pixels[lo].count; ++k)
    if (list->traces[k][0] == gl_fragments && list->traces[k][1] == (unsigned)ids &&
        list->traces[k][2] == (unsigned)hashes)
      return 1;
  return 0;
}

/* The label of pixel i's coverage by `verdict` (rows indexed by edge bits; `counts_checked`: the
   reference has fragment counts to compare), from what GL kept there (gl_primitive; `candidate`,
   GL's primitive among the pixel's candidates of the depth test, or NULL), its fragment count
   and its trace (read only where its outcome changes the label). */
static enum label pixel_label(const verdict_row *verdict, int counts_checked,
                              const struct trace_list *traces, int i,
                              const struct expected_coverage *expected, int gl_primitive,
                              unsigned gl_fragments, const float *trace,
                              const struct candidate *candidate) {
  const enum kept kept = gl_primitive == expected->primitive ? KEPT_REFERENCE
                         : candidate                         ? KEPT_CANDIDATE
                                                             : KEPT_OTHER;
  const enum count count = !counts_checked || gl_fragments == expected->fragments ? COUNT_SAME
                           : gl_fragments < expected->fragments                  ? COUNT_FEWER
                                                                                 : COUNT_MORE;
  const unsigned char *labels = verdict[expected->edges][kept][count];
  if (labels[0] == labels[1]) return (enum label)labels[1];
  return (enum label)labels[trace_admitted(traces, i, gl_fragments, trace)];
}
