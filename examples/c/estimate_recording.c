/* Replays a dlw recording through the C estimator and prints one angle per sample.
 *
 *   cc -I crates/estimator-ffi/include examples/c/estimate_recording.c \
 *      target/release/libdlw_estimator.a -lm -lpthread -ldl -o estimate_recording
 *   ./estimate_recording config.toml recording/data.csv > angles.txt
 *
 * It reads the columns v1_V and (if present) v2_V of data.csv and passes them to
 * dlw_estimator_step; a one-sensor config ignores v2. Each output line is
 * "estimate_deg,flags" with 17 significant digits, the same numbers as the estimate_deg
 * column of `dlw estimate --precision 15`. Exit status 1 on any error, with the reason on
 * stderr. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "dlw_estimator.h"

static char *read_file(const char *path) {
    FILE *f = fopen(path, "rb");
    if (!f) return NULL;
    if (fseek(f, 0, SEEK_END) != 0) { fclose(f); return NULL; }
    long n = ftell(f);
    if (n < 0 || fseek(f, 0, SEEK_SET) != 0) { fclose(f); return NULL; }
    char *text = malloc((size_t)n + 1);
    if (text && fread(text, 1, (size_t)n, f) != (size_t)n) { free(text); text = NULL; }
    if (text) text[n] = '\0';
    fclose(f);
    return text;
}

/* Index of the column named `name` in the CSV header line, or -1. */
static int column(char *header, const char *name) {
    int i = 0;
    char copy[1024];
    strncpy(copy, header, sizeof copy - 1);
    copy[sizeof copy - 1] = '\0';
    for (char *tok = strtok(copy, ",\r\n"); tok; tok = strtok(NULL, ",\r\n"), i++)
        if (strcmp(tok, name) == 0) return i;
    return -1;
}

/* The number in column `index` of a CSV line. */
static double field(const char *line, int index) {
    const char *p = line;
    for (int i = 0; i < index && p; i++) {
        p = strchr(p, ',');
        if (p) p++;
    }
    return p ? strtod(p, NULL) : 0.0;
}

int main(int argc, char **argv) {
    if (argc != 3) {
        fprintf(stderr, "usage: %s CONFIG.toml DATA.csv\n", argv[0]);
        return 1;
    }
    char *config = read_file(argv[1]);
    if (!config) { fprintf(stderr, "cannot read %s\n", argv[1]); return 1; }
    char error[512];
    DlwEstimator *e = dlw_estimator_from_toml(config, error, sizeof error);
    free(config);
    if (!e) { fprintf(stderr, "%s: %s\n", argv[1], error); return 1; }

    FILE *data = fopen(argv[2], "r");
    if (!data) { fprintf(stderr, "cannot read %s\n", argv[2]); dlw_estimator_free(e); return 1; }
    char line[1024];
    if (!fgets(line, sizeof line, data)) {
        fprintf(stderr, "%s is empty\n", argv[2]);
        fclose(data); dlw_estimator_free(e); return 1;
    }
    int c1 = column(line, "v1_V"), c2 = column(line, "v2_V");
    if (c1 < 0) {
        fprintf(stderr, "%s has no v1_V column\n", argv[2]);
        fclose(data); dlw_estimator_free(e); return 1;
    }
    int status = 0;
    while (fgets(line, sizeof line, data)) {
        double v1 = field(line, c1), v2 = c2 >= 0 ? field(line, c2) : 0.0;
        double angle;
        uint32_t flags;
        int rc = dlw_estimator_step(e, v1, v2, &angle, &flags);
        if (rc != DLW_OK) { fprintf(stderr, "dlw_estimator_step failed: %d\n", rc); status = 1; break; }
        printf("%.17g,%u\n", angle, (unsigned)flags);
    }
    fclose(data);
    dlw_estimator_free(e);
    return status;
}
