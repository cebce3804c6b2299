package io.dtron.model;

import java.util.ArrayList;
import java.util.Collection;
import java.util.Comparator;
import java.util.LinkedHashSet;
import java.util.List;
import java.util.Locale;

/**
 * The names nearest to a misspelt one, for "did you mean" hints in error messages: by edit distance (insertions,
 * deletions, substitutions and swaps of two neighbouring characters, case ignored), at most a third of the name's
 * length (at least 1, and less than the whole name); of those, the nearest ones, {@value #MAX} at most.
 */
public final class NearestNames {
    /** The most names a hint offers. */
    public static final int MAX = 3;

    private NearestNames() {
    }

    /**
     * The names of {@code candidates} nearest to {@code name}, ordered by their distance with case, then
     * alphabetically.
     */
    public static List<String> of(String name, Collection<String> candidates) {
        String lower = name.toLowerCase(Locale.ROOT);
        int limit = Math.min(Math.max(1, name.length() / 3), name.length() - 1);
        record Near(String name, int distance, int exactDistance) {
        }
        List<Near> near = new ArrayList<>();
        for (String c : new LinkedHashSet<>(candidates)) {
            if (c.equals(name)) {
                continue;
            }
            int d = distance(lower, c.toLowerCase(Locale.ROOT));
            if (d <= limit) {
                near.add(new Near(c, d, distance(name, c)));
            }
        }
        int nearest = near.stream().mapToInt(Near::distance).min().orElse(0);
        return near.stream().filter(n -> n.distance() == nearest)
                .sorted(Comparator.comparingInt(Near::exactDistance).thenComparing(Near::name))
                .limit(MAX).map(Near::name).toList();
    }

    /**
     * A hint to append to an error message about {@code name}: {@code " (did you mean 'Train'?)"}, {@code " (did you
     * mean 'a' or 'b'?)"}, or the empty string when no candidate is near.
     */
    public static String hint(String name, Collection<String> candidates) {
        return didYouMean(of(name, candidates));
    }

    /** {@code " (did you mean 'a', 'b' or 'c'?)"} for these names, or the empty string when there are none. */
    public static String didYouMean(List<String> near) {
        if (near.isEmpty()) {
            return "";
        }
        StringBuilder sb = new StringBuilder(" (did you mean ");
        for (int i = 0; i < near.size(); i++) {
            sb.append(i == 0 ? "" : i == near.size() - 1 ? " or " : ", ").append('\'').append(near.get(i)).append('\'');
        }
        return sb.append("?)").toString();
    }

    /** The optimal-string-alignment distance: Levenshtein's with a swap of two neighbours as one edit. */
    static int distance(String a, String b) {
        int[][] d = new int[a.length() + 1][b.length() + 1];
        for (int i = 0; i <= a.length(); i++) {
            d[i][0] = i;
        }
        for (int j = 0; j <= b.length(); j++) {
            d[0][j] = j;
        }
        for (int i = 1; i <= a.length(); i++) {
            for (int j = 1; j <= b.length(); j++) {
                int cost = a.charAt(i - 1) == b.charAt(j - 1) ? 0 : 1;
                d[i][j] = Math.min(Math.min(d[i - 1][j] + 1, d[i][j - 1] + 1), d[i - 1][j - 1] + cost);
                if (i > 1 && j > 1 && a.charAt(i - 1) == b.charAt(j - 2) && a.charAt(i - 2) == b.charAt(j - 1)) {
                    d[i][j] = Math.min(d[i][j], d[i - 2][j - 2] + 1);
                }
            }
        }
        return d[a.length()][b.length()];
    }
}
