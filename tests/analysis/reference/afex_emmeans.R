# Reference values of the mixed-design conventions (tests/analysis/followups/test_mixed_conventions.py), computed with R's
# afex (ANOVA, sums of squares of type 3 and 2, sphericity corrections) and emmeans (follow-ups on the model afex
# fits: its default multivariate model, the within-group covariance pooled over the groups).
#
#   Rscript tests/analysis/reference/afex_emmeans.R PINGOUIN_DATASETS_DIR tests/analysis/reference/afex_emmeans.csv
#
# PINGOUIN_DATASETS_DIR holds pingouin's mixed_anova.csv (python -c "import pingouin, os;
# print(os.path.join(os.path.dirname(pingouin.__file__), 'datasets'))"). Written with R 4.2.2, afex 1.2-1,
# emmeans 1.8.4 and car 3.1-1 (Debian bookworm's r-base-core, r-cran-afex, r-cran-emmeans, r-cran-car); the
# versions are the file's first line. Values have 12 significant digits, except emmeans' joint-test F, which
# emmeans rounds to 3 decimals (its p is not rounded).
#
# Datasets:
#   pingouin_mixed         pingouin's "mixed_anova" dataset (its mixed_anova example): Scores of 60 subjects,
#                          Group (Control, Meditation; 30 each) × Time (August, January, June)
#   pingouin_unbalanced    the same without the eight Meditation subjects with the lowest ids (30-37): 30 and 22
#   obrien_kaiser          O'Brien & Kaiser (1985), afex's obk.long (car's OBrienKaiser): 16 subjects,
#                          treatment (control 5, A 4, B 7) × phase (pre, post, fup) × hour (1-5); gender left out
suppressMessages({library(afex); library(emmeans)})
args <- commandArgs(trailingOnly = TRUE)
versions <- sprintf("R %s.%s, afex %s, emmeans %s, car %s", R.version$major, R.version$minor,
                    packageVersion("afex"), packageVersion("emmeans"), packageVersion("car"))
rows <- list()
unx <- function(text) gsub("\\bX([0-9])", "\\1", text)  # afex names a numeric level 1 as X1
add <- function(dataset, package, statistic, term, by, contrast, value) {
  rows[[length(rows) + 1]] <<- data.frame(dataset = dataset, package = package, statistic = statistic, term = term,
                                          by = unx(by), contrast = unx(contrast), value = format(value, digits = 12))
}
by_label <- function(frame, names) {
  if (length(names) == 0) return(rep("", nrow(frame)))
  apply(frame[, names, drop = FALSE], 1, function(r) paste(paste0(names, "=", trimws(r)), collapse = ", "))
}

anova_rows <- function(dataset, fit, type) {
  a <- anova(fit, es = "ges", correction = "none")
  for (term in rownames(a)) {
    add(dataset, "afex", paste0("F_type", type), term, "", "", a[term, "F"])
    add(dataset, "afex", paste0("p_type", type), term, "", "", a[term, "Pr(>F)"])
    add(dataset, "afex", paste0("ges_type", type), term, "", "", a[term, "ges"])
    add(dataset, "afex", paste0("MSE_type", type), term, "", "", a[term, "MSE"])
  }
  s <- summary(fit)$pval.adjustments
  if (!is.null(s) && length(s) > 0) {
    for (term in rownames(s)) {
      add(dataset, "afex", paste0("eps_gg_type", type), term, "", "", s[term, "GG eps"])
      add(dataset, "afex", paste0("p_gg_type", type), term, "", "", s[term, "Pr(>F[GG])"])
      add(dataset, "afex", paste0("eps_hf_type", type), term, "", "", s[term, "HF eps"])
      add(dataset, "afex", paste0("p_hf_type", type), term, "", "", s[term, "Pr(>F[HF])"])
    }
  }
}

pair_rows <- function(dataset, fit, spec, by) {
  em <- emmeans(fit, spec, by = by)
  for (adjust in c("none", "holm")) {
    p <- as.data.frame(summary(pairs(em, adjust = adjust), infer = TRUE))
    label <- by_label(p, by)
    for (i in seq_len(nrow(p))) {
      contrast <- as.character(p$contrast[i])
      if (adjust == "none") {
        add(dataset, "emmeans", "estimate", spec, label[i], contrast, p$estimate[i])
        add(dataset, "emmeans", "SE", spec, label[i], contrast, p$SE[i])
        add(dataset, "emmeans", "df", spec, label[i], contrast, p$df[i])
        add(dataset, "emmeans", "t", spec, label[i], contrast, p$t.ratio[i])
        add(dataset, "emmeans", "p", spec, label[i], contrast, p$p.value[i])
        add(dataset, "emmeans", "lower.CL", spec, label[i], contrast, p$lower.CL[i])
        add(dataset, "emmeans", "upper.CL", spec, label[i], contrast, p$upper.CL[i])
      } else {
        add(dataset, "emmeans", "p_holm", spec, label[i], contrast, p$p.value[i])
      }
    }
  }
}

joint_rows <- function(dataset, fit, by) {
  j <- as.data.frame(joint_tests(fit, by = by))
  label <- by_label(j, by)
  for (i in seq_len(nrow(j))) {
    term <- trimws(as.character(j$`model term`[i]))
    add(dataset, "emmeans", "F", term, label[i], "", j$F.ratio[i])
    add(dataset, "emmeans", "df2", term, label[i], "", j$df2[i])
    add(dataset, "emmeans", "p", term, label[i], "", j$p.value[i])
  }
}

mixed <- read.csv(file.path(args[1], "mixed_anova.csv"))
mixed$Subject <- factor(mixed$Subject)
mixed$Group <- factor(mixed$Group, levels = c("Control", "Meditation"))
mixed$Time <- factor(mixed$Time, levels = c("August", "January", "June"))
unbalanced <- droplevels(mixed[!(mixed$Group == "Meditation" & as.integer(as.character(mixed$Subject)) %in% 30:37), ])
for (set in list(list("pingouin_mixed", mixed), list("pingouin_unbalanced", unbalanced))) {
  for (type in c(3, 2)) {
    fit <- aov_car(Scores ~ Group * Time + Error(Subject / Time), data = set[[2]], type = type)
    anova_rows(set[[1]], fit, type)
  }
  fit <- aov_car(Scores ~ Group * Time + Error(Subject / Time), data = set[[2]], type = 3)
  pair_rows(set[[1]], fit, "Time", "Group")
  joint_rows(set[[1]], fit, "Group")
  joint_rows(set[[1]], fit, "Time")
}

data(obk.long, package = "afex")
obk <- obk.long
obk$phase <- factor(obk$phase, levels = c("pre", "post", "fup"))
for (type in c(3, 2)) {
  fit <- aov_car(value ~ treatment * phase * hour + Error(id / (phase * hour)), data = obk, type = type)
  anova_rows("obrien_kaiser", fit, type)
}
fit <- aov_car(value ~ treatment * phase * hour + Error(id / (phase * hour)), data = obk, type = 3)
pair_rows("obrien_kaiser", fit, "phase", "treatment")
pair_rows("obrien_kaiser", fit, "hour", "treatment")
pair_rows("obrien_kaiser", fit, "phase", c("treatment", "hour"))
pair_rows("obrien_kaiser", fit, "hour", c("treatment", "phase"))
pair_rows("obrien_kaiser", fit, "treatment", character(0))
joint_rows("obrien_kaiser", fit, c("treatment", "hour"))
joint_rows("obrien_kaiser", fit, c("treatment", "phase"))
joint_rows("obrien_kaiser", fit, c("phase", "hour"))

out <- do.call(rbind, rows)
writeLines(paste("#", versions), args[2])
suppressWarnings(write.table(out, args[2], sep = ",", row.names = FALSE, append = TRUE))
cat(nrow(out), "reference values written to", args[2], "\n")
