/* SPDX-License-Identifier: BSD-2-Clause */
/* The options of every command, from one table (cli_args.h). */
#define _GNU_SOURCE /* getopt_long */
#include "cli_args.h"

#include <float.h>
#include <getopt.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include "brdfwave/brdfwave.h"
#include "cli_errors.h"
#include "cli_num.h"

#define MAX_OPTS 60
#define VAL_BASE 256 /* getopt_long's value of table entry i: VAL_BASE + i */
#define HELP (VAL_BASE + MAX_OPTS)
#define VERSION (HELP + 1)

/* "PROG VERSION", the answer of --version */
static void print_version(const char *prog)
{
    printf("%s %s (libbrdfwave %s)\n"
           "Copyright the brdfwave authors; BSD-2-Clause licence (LICENSE).\n",
           prog, BRDFWAVE_VERSION_STRING, bwh_version());
}

static int takes_value(const cli_opt_t *o) { return o->kind != CLI_FLAG; }

/* "--name" of a long option as typed, without "=value" */
static void typed_name(const char *arg, char *out, size_t cap)
{
    size_t n = strcspn(arg, "=");
    if (n >= cap)
        n = cap - 1;
    memcpy(out, arg, n);
    out[n] = 0;
}

/* Damerau-Levenshtein distance (adjacent transpositions count 1), for
 * names of up to 63 characters */
static int distance(const char *a, const char *b)
{
    size_t la = strlen(a), lb = strlen(b);
    if (la > 63 || lb > 63)
        return 99;
    int d[64][64];
    for (size_t i = 0; i <= la; i++)
        d[i][0] = (int)i;
    for (size_t j = 0; j <= lb; j++)
        d[0][j] = (int)j;
    for (size_t i = 1; i <= la; i++)
        for (size_t j = 1; j <= lb; j++) {
            int cost = a[i - 1] != b[j - 1];
            int v = d[i - 1][j] + 1;
            if (d[i][j - 1] + 1 < v)
                v = d[i][j - 1] + 1;
            if (d[i - 1][j - 1] + cost < v)
                v = d[i - 1][j - 1] + cost;
            if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1] &&
                d[i - 2][j - 2] + 1 < v)
                v = d[i - 2][j - 2] + 1;
            d[i][j] = v;
        }
    return d[la][lb];
}

/* the option name closest to `name` (without dashes), if close enough */
static const char *closest(const cli_opt_t *opts, const char *name)
{
    const char *best = NULL;
    int bd = 99;
    for (const cli_opt_t *o = opts; o->name; o++) {
        int dd = distance(name, o->name);
        if (dd < bd) {
            bd = dd;
            best = o->name;
        }
    }
    static const char *const added[] = {"help", "version"};
    for (size_t k = 0; k < sizeof added / sizeof *added; k++) {
        int dh = distance(name, added[k]);
        if (dh < bd) {
            bd = dh;
            best = added[k];
        }
    }
    size_t len = strlen(name);
    return bd <= (len > 6 ? 2 : 1) ? best : NULL;
}

static int unknown_long(const cli_opt_t *opts, const char *arg)
{
    char typed[128];
    typed_name(arg, typed, sizeof typed);
    const char *name = typed + 2;
    /* an abbreviation that fits more than one option */
    char list[512] = "";
    int fits = 0;
    for (const cli_opt_t *o = opts; o->name; o++)
        if (*name && !strncmp(o->name, name, strlen(name))) {
            size_t l = strlen(list);
            snprintf(list + l, sizeof list - l, "%s--%s", fits ? ", " : "", o->name);
            fits++;
        }
    if (fits > 1)
        return cli_usage("option '%s' is ambiguous (%s)", typed, list);
    const char *guess = closest(opts, name);
    if (guess)
        return cli_usage_plain("unknown option '%s' (did you mean '--%s'?)", typed, guess);
    return cli_usage("unknown option '%s'", typed);
}

/* "--name" of entry o, for messages */
static const char *shown(const cli_opt_t *o, char *buf, size_t cap)
{
    snprintf(buf, cap, "--%s", o->name);
    return buf;
}

static int bad_value(const cli_opt_t *o, const char *v)
{
    char n[80];
    shown(o, n, sizeof n);
    if (o->what)
        return cli_usage("%s", o->what);
    switch (o->kind) {
    case CLI_U32:
        return cli_usage("%s needs an integer %.0f..%.0f, got '%s'", n, o->lo, o->hi, v);
    case CLI_REAL:
        return cli_usage("%s needs a number in [%g, %g], got '%s'", n, o->lo, o->hi, v);
    case CLI_POSITIVE:
        return cli_usage("%s needs a number > 0, got '%s'", n, v);
    case CLI_CHOICE: {
        char list[256] = "";
        for (int k = 0; o->choices[k]; k++) {
            size_t l = strlen(list);
            snprintf(list + l, sizeof list - l, "%s%s", k ? (o->choices[k + 1] ? ", " : " or ")
                                                          : "",
                     o->choices[k]);
        }
        return cli_usage("%s needs %s, got '%s'", n, list, v);
    }
    default:
        return cli_usage("%s: bad value '%s'", n, v);
    }
}

/* stores value v of option o; 0, or the usage status */
static int take(const cli_opt_t *o, const char *v)
{
    if (o->seen)
        ++*o->seen;
    switch (o->kind) {
    case CLI_FLAG:
        *(int *)o->dest = 1;
        return 0;
    case CLI_STRING:
        *(const char **)o->dest = v;
        return 0;
    case CLI_LIST: {
        cli_list_t *l = o->dest;
        if (l->n == l->cap) {
            char n[80];
            return cli_usage("at most %d %s options", l->cap, shown(o, n, sizeof n));
        }
        l->item[l->n++] = v;
        return 0;
    }
    case CLI_U32: {
        uint32_t x;
        if (cli_u32(v, (uint32_t)o->lo, (uint32_t)o->hi, o->hex, &x) != 0)
            return bad_value(o, v);
        *(uint32_t *)o->dest = x;
        return 0;
    }
    case CLI_REAL:
        return cli_real(v, o->lo, o->hi, (double *)o->dest) != 0 ? bad_value(o, v) : 0;
    case CLI_POSITIVE:
        return cli_positive(v, o->hi > 0 ? o->hi : DBL_MAX, (double *)o->dest) != 0
                   ? bad_value(o, v)
                   : 0;
    case CLI_CHOICE:
        for (int k = 0; o->choices[k]; k++)
            if (!strcmp(v, o->choices[k])) {
                *(int *)o->dest = k;
                return 0;
            }
        return bad_value(o, v);
    case CLI_CALL:
        return o->parse(v, o->dest) != 0 ? bad_value(o, v) : 0;
    }
    return bad_value(o, v);
}

bool cli_parse(int argc, char **argv, const cli_opt_t *opts, const char *help, int *first,
               int *status)
{
    struct option lo[MAX_OPTS + 3];
    char shorts[3 * MAX_OPTS + 8];
    size_t ns = 0, n = 0;
    shorts[ns++] = ':'; /* a missing value is reported as such */
    for (; opts[n].name; n++) {
        if (n == MAX_OPTS) {
            *status = cli_fail("internal error: more than %d options", MAX_OPTS);
            return false;
        }
        const cli_opt_t *o = &opts[n];
        lo[n] = (struct option){o->name, takes_value(o) ? required_argument : no_argument, NULL,
                                VAL_BASE + (int)n};
        if (o->letter) {
            shorts[ns++] = o->letter;
            if (takes_value(o))
                shorts[ns++] = ':';
        }
    }
    lo[n] = (struct option){"help", no_argument, NULL, HELP};
    lo[n + 1] = (struct option){"version", no_argument, NULL, VERSION};
    lo[n + 2] = (struct option){NULL, 0, NULL, 0};
    shorts[ns++] = 'h';
    shorts[ns] = 0;

#ifdef __GLIBC__
    optind = 0; /* full re-initialisation of getopt's state */
#else
    optind = 1;
#endif
    opterr = 0;
    int c;
    while ((c = getopt_long(argc, argv, shorts, lo, NULL)) != -1) {
        const cli_opt_t *o = NULL;
        if (c >= VAL_BASE && c < VAL_BASE + (int)n)
            o = &opts[c - VAL_BASE];
        else if (c != '?' && c != ':' && c != 'h' && c != HELP)
            for (size_t k = 0; k < n && !o; k++)
                if (opts[k].letter == c)
                    o = &opts[k];
        if (c == 'h' || c == HELP) {
            fputs(help, stdout);
            *status = CLI_EXIT_OK;
            return false;
        }
        if (c == VERSION) {
            print_version(cli_prog());
            *status = CLI_EXIT_OK;
            return false;
        }
        if (o) {
            int st = take(o, optarg);
            if (st) {
                *status = st;
                return false;
            }
            continue;
        }
        const char *arg = argv[optind - 1];
        char name[80];
        int opt = optopt;
        const cli_opt_t *which = NULL;
        if (opt >= VAL_BASE && opt < VAL_BASE + (int)n)
            which = &opts[opt - VAL_BASE];
        else
            for (size_t k = 0; k < n && opt > 0 && !which; k++)
                if (opts[k].letter == opt)
                    which = &opts[k];
        if (c == ':')
            *status = cli_usage("option '%s' needs a value",
                                which ? shown(which, name, sizeof name) : arg);
        else if (which && !takes_value(which))
            *status = cli_usage("option '%s' takes no value", shown(which, name, sizeof name));
        else if (opt > 0 && opt < VAL_BASE)
            *status = cli_usage("unknown option '-%c'", opt);
        else if (!strncmp(arg, "--", 2))
            *status = unknown_long(opts, arg);
        else
            *status = cli_usage("unknown option '%s'", arg);
        return false;
    }
    if (!first && optind < argc) {
        *status = cli_usage("unexpected argument '%s'", argv[optind]);
        return false;
    }
    if (first)
        *first = optind;
    return true;
}

int cli_dispatch(const char *prog, const cli_command_t *cmds, size_t n, int argc, char **argv,
                 void (*usage)(FILE *f))
{
    cli_set_name(prog, "");
    if (argc < 2) {
        usage(stderr);
        return CLI_EXIT_USAGE;
    }
    if (!strcmp(argv[1], "-h") || !strcmp(argv[1], "--help") || !strcmp(argv[1], "help")) {
        usage(stdout);
        return CLI_EXIT_OK;
    }
    if (!strcmp(argv[1], "-V") || !strcmp(argv[1], "--version")) {
        print_version(prog);
        return CLI_EXIT_OK;
    }
    for (size_t i = 0; i < n; i++)
        if (!strcmp(argv[1], cmds[i].name)) {
            cli_set_name(prog, cmds[i].name);
            return cmds[i].run(argc - 1, argv + 1);
        }
    return cli_usage("unknown command '%s'", argv[1]);
}
