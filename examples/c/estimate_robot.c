/* Replays a robot recording through the C robot estimator and prints, per sample, every
 * joint's angle, the tip's position and every joint's flags.
 *
 *   cc -I crates/estimator-ffi/include examples/c/estimate_robot.c \
 *      target/release/libdlw_estimator.a -lm -lpthread -ldl -o estimate_robot
 *   ./estimate_robot robot-config.toml recording/data.csv > estimates.txt
 *
 * It reads the columns v1_V .. vM_V of data.csv (M: the config's sensors, in its order) and
 * passes them to dlw_robot_estimator_step, then the angles to dlw_robot_estimator_tip. Each
 * output line is "angle1_deg,..,angleN_deg,tip_x_mm,tip_y_mm,tip_z_mm,flags1,..,flagsN" with
 * 17 significant digits. Exit status 1 on any error, with the reason on stderr (and nothing on
 * stdout for a config or file it cannot use). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "dlw_estimator.h"

#define LINE 16384

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
static int column(const char *header, const char *name) {
    static char copy[LINE];
    int i = 0;
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
        fprintf(stderr, "usage: %s ROBOT-CONFIG.toml DATA.csv\n", argv[0]);
        return 1;
    }
    char *config = read_file(argv[1]);
    if (!config) { fprintf(stderr, "cannot read %s\n", argv[1]); return 1; }
    char error[512];
    DlwRobotEstimator *e = dlw_robot_estimator_from_toml(config, error, sizeof error);
    free(config);
    if (!e) { fprintf(stderr, "%s: %s\n", argv[1], error); return 1; }
    size_t joints = dlw_robot_estimator_joints(e), sensors = dlw_robot_estimator_sensors(e);

    FILE *data = fopen(argv[2], "r");
    if (!data) { fprintf(stderr, "cannot read %s\n", argv[2]); dlw_robot_estimator_free(e); return 1; }
    static char line[LINE];
    if (!fgets(line, sizeof line, data)) {
        fprintf(stderr, "%s is empty\n", argv[2]);
        fclose(data); dlw_robot_estimator_free(e); return 1;
    }
    int columns[DLW_MAX_SENSORS];
    for (size_t i = 0; i < sensors; i++) {
        char name[32];
        snprintf(name, sizeof name, "v%zu_V", i + 1);
        columns[i] = column(line, name);
        if (columns[i] < 0) {
            fprintf(stderr, "%s has no %s column (the config has %zu sensors)\n", argv[2], name, sensors);
            fclose(data); dlw_robot_estimator_free(e); return 1;
        }
    }
    int status = 0;
    while (fgets(line, sizeof line, data)) {
        double volts[DLW_MAX_SENSORS], angles[DLW_MAX_JOINTS];
        double position[3], rotation[9], quaternion[4];
        uint32_t flags[DLW_MAX_JOINTS];
        for (size_t i = 0; i < sensors; i++) volts[i] = field(line, columns[i]);
        int rc = dlw_robot_estimator_step(e, volts, sensors, angles, flags, joints);
        if (rc == DLW_OK) rc = dlw_robot_estimator_tip(e, angles, joints, position, rotation, quaternion);
        if (rc != DLW_OK) { fprintf(stderr, "dlw_robot_estimator failed: %d\n", rc); status = 1; break; }
        for (size_t j = 0; j < joints; j++) printf("%.17g,", angles[j]);
        printf("%.17g,%.17g,%.17g", position[0], position[1], position[2]);
        for (size_t j = 0; j < joints; j++) printf(",%u", (unsigned)flags[j]);
        printf("\n");
    }
    fclose(data);
    dlw_robot_estimator_free(e);
    return status;
}
