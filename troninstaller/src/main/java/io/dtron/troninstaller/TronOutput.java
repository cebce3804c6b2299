package io.dtron.troninstaller;

import java.util.Locale;
import java.util.Optional;
import java.util.OptionalInt;
import java.util.OptionalLong;
import java.util.regex.Matcher;
import java.util.regex.Pattern;

/**
 * The verdict and the seed read from what TRON printed.
 *
 * <p>TRON's exact output is not documented for DTRON, so this reads an <em>assumed</em> format, tolerant of
 * variations:
 * <ul>
 *   <li>the statistics line {@code SEED VERDICT #INPUTS #OUTPUTS DURATION} (TRON's format, e.g. {@code 42 FAILED 3 5
 *       271000}) gives the seed, the verdict and the counts;</li>
 *   <li>otherwise the verdict is on the last line where one of the words {@code PASSED}, {@code FAILED}, {@code
 *       INCONCLUSIVE} follows {@code TEST}, {@code Verdict:} or starts the line ({@code TEST FAILED: output level
 *       too late}); the text after the word and a colon is the explanation;</li>
 *   <li>the seed is the number after the word {@code seed} ({@code Random seed: 42}, {@code seed 42}).</li>
 * </ul>
 * DTRON's own {@code dtron tron} command prints these lines, so that scripts reading TRON's output read DTRON's too.
 */
public final class TronOutput {
    private static final Pattern STATISTICS = Pattern.compile(
            "^\\s*(-?\\d+)\\s+(PASSED|FAILED|INCONCLUSIVE)\\s+(\\d+)\\s+(\\d+)\\s+\\S+\\s*$");
    private static final Pattern VERDICT = Pattern.compile("^\\s*(?:(?:TEST|Test|test)\\s+|(?i:verdict)\\s*[:=]?\\s*)?"
            + "(PASSED|FAILED|INCONCLUSIVE)\\b\\s*[:.,-]?\\s*(.*)$");
    private static final Pattern SEED = Pattern.compile("\\bseed\\b\\s*[:=]?\\s*(-?\\d+)", Pattern.CASE_INSENSITIVE);

    private final String verdict;
    private final String explanation;
    private final Long seed;
    private final Integer inputs;
    private final Integer outputs;

    private TronOutput(String verdict, String explanation, Long seed, Integer inputs, Integer outputs) {
        this.verdict = verdict;
        this.explanation = explanation;
        this.seed = seed;
        this.inputs = inputs;
        this.outputs = outputs;
    }

    /** Reads TRON's output. */
    public static TronOutput parse(String text) {
        String verdict = null;
        String explanation = null;
        Long seed = null;
        Integer inputs = null;
        Integer outputs = null;
        for (String line : text.split("\\R")) {
            Matcher stats = STATISTICS.matcher(line);
            if (stats.matches()) {
                seed = Long.parseLong(stats.group(1));
                inputs = Integer.parseInt(stats.group(3));
                outputs = Integer.parseInt(stats.group(4));
                if (verdict == null) {
                    verdict = stats.group(2);
                }
                continue;
            }
            Matcher v = VERDICT.matcher(line);
            if (v.matches()) {
                verdict = v.group(1);
                explanation = v.group(2).isBlank() ? null : v.group(2).strip();
            }
            Matcher s = SEED.matcher(line);
            if (s.find() && seed == null) {
                seed = Long.parseLong(s.group(1));
            }
        }
        return new TronOutput(verdict == null ? null : verdict.toUpperCase(Locale.ROOT), explanation, seed, inputs,
                outputs);
    }

    /** The verdict word: {@code PASSED}, {@code FAILED} or {@code INCONCLUSIVE}, if TRON printed one. */
    public Optional<String> verdict() {
        return Optional.ofNullable(verdict);
    }

    /** The text after the verdict word, if any. */
    public Optional<String> explanation() {
        return Optional.ofNullable(explanation);
    }

    /** The random seed TRON printed, if any. */
    public OptionalLong seed() {
        return seed == null ? OptionalLong.empty() : OptionalLong.of(seed);
    }

    /** The number of inputs from the statistics line, if there was one. */
    public OptionalInt inputs() {
        return inputs == null ? OptionalInt.empty() : OptionalInt.of(inputs);
    }

    /** The number of outputs from the statistics line, if there was one. */
    public OptionalInt outputs() {
        return outputs == null ? OptionalInt.empty() : OptionalInt.of(outputs);
    }
}
