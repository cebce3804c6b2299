package io.dtron.engine.internal.verify;

import io.dtron.engine.verify.Query;
import io.dtron.engine.verify.QueryException;
import java.util.ArrayList;
import java.util.List;
import java.util.regex.Matcher;
import java.util.regex.Pattern;

/**
 * Splits a query into its path quantifier and state properties, and recognises the query forms of Uppaal that
 * the checker does not check (statistical, optimisation and strategy queries), so that they are skipped with a
 * reason. The state properties themselves are parsed and resolved by {@link PropertyCompiler}.
 */
public final class QueryParser {
    private static final Pattern QUANTIFIER = Pattern.compile("^(E\\s*<>|A\\s*\\[\\s*]|E\\s*\\[\\s*]|A\\s*<>)");

    /** Prefixes of the query forms that are skipped, with the reason. */
    private static final List<Object[]> SKIPPED = List.of(
            new Object[] {Pattern.compile("^Pr\\b"), "a probability estimate (statistical model checking) is not"
                    + " checked: DTRON's checker is symbolic"},
            new Object[] {Pattern.compile("^simulate\\b"), "simulation queries are not checked: DTRON's checker is"
                    + " symbolic"},
            new Object[] {Pattern.compile("^E\\s*\\[(?!\\s*])"), "an expected-value query (statistical model"
                    + " checking) is not checked: DTRON's checker is symbolic"},
            new Object[] {Pattern.compile("^(sup|inf)\\b"), "supremum and infimum queries are not checked"},
            new Object[] {Pattern.compile("^(control|control_t|E\\s*<>\\s*control)\\b|^A\\s*\\[\\s*]\\s*control\\b"),
                    "controller synthesis is not checked"},
            new Object[] {Pattern.compile("^(strategy|saveStrategy|loadStrategy|minE|maxE|minPr|maxPr)\\b"),
                    "strategy queries are not checked"},
            new Object[] {Pattern.compile("^bounds\\b"), "bounds queries are not checked"});
    private static final Pattern UNDER_STRATEGY = Pattern.compile("\\bunder\\s+\\w+\\s*$");
    /** Implication as other logics write it: {@code ->} (not the end of {@code -->}) and {@code implies}. */
    private static final Pattern IMPLICATION = Pattern.compile("(?<!-)->|\\bimplies\\b");

    private QueryParser() {
    }

    /** Parses one query; see {@link Query#parse}. */
    public static Query parse(String written) {
        String text = written.strip();
        if (text.isEmpty()) {
            throw new QueryException("empty query");
        }
        for (Object[] skipped : SKIPPED) {
            if (((Pattern) skipped[0]).matcher(text).find()) {
                return new Query(text, Query.Kind.UNSUPPORTED, null, null, (String) skipped[1], 0, 0);
            }
        }
        if (UNDER_STRATEGY.matcher(text).find()) {
            return new Query(text, Query.Kind.UNSUPPORTED, null, null, "queries under a strategy are not checked", 0,
                    0);
        }
        Matcher m = QUANTIFIER.matcher(text);
        if (m.find()) {
            String q = m.group(1).replaceAll("\\s", "");
            Query.Kind kind = switch (q) {
                case "E<>" -> Query.Kind.EXISTS_EVENTUALLY;
                case "A[]" -> Query.Kind.ALWAYS_GLOBALLY;
                case "E[]" -> Query.Kind.EXISTS_GLOBALLY;
                default -> Query.Kind.ALWAYS_EVENTUALLY;
            };
            int start = skipSpaces(text, m.end());
            String property = text.substring(start);
            if (property.isBlank()) {
                throw new QueryException("query '" + text + "', column " + (start + 1) + ": a state property is"
                        + " missing after " + q);
            }
            return new Query(text, kind, property, null, null, start + 1, 0);
        }
        int arrow = topLevelArrow(text);
        if (arrow >= 0) {
            String premise = text.substring(0, arrow).strip();
            int targetStart = skipSpaces(text, arrow + 3);
            String target = text.substring(targetStart);
            if (premise.isEmpty() || target.isBlank()) {
                throw new QueryException("query '" + text + "', column " + (premise.isEmpty() ? 1 : targetStart + 1)
                        + ": a leads-to query needs a state property on each side of -->");
            }
            return new Query(text, Query.Kind.LEADS_TO, premise, target, null, 1, 0);
        }
        Matcher implication = IMPLICATION.matcher(text);
        if (implication.find()) {
            throw new QueryException("query '" + text + "', column " + (implication.start() + 1) + ": "
                    + implicationMistake(text, implication.start(), true));
        }
        throw new QueryException("query '" + text + "', column 1: not a query: expected E<> p, A[] p, E[] p, A<> p"
                + " or p --> q");
    }

    /**
     * The error for an implication written as other logics write it ({@code ->}, {@code implies}) at offset
     * {@code at} of {@code text}, saying how queries write it, or null when there is none there.
     *
     * @param wholeQuery whether {@code text} is a whole query without a path quantifier, which may have meant
     *                   leads-to ({@code p --> q}) too
     */
    static String implicationMistake(String text, int at, boolean wholeQuery) {
        Matcher m = IMPLICATION.matcher(text).useTransparentBounds(true).region(at, text.length());
        if (!m.lookingAt()) {
            return null;
        }
        return "'" + m.group() + "' is not an operator of queries: implication is written imply"
                + (wholeQuery ? " (A[] p imply q), and a leads-to query p --> q" : ", as in p imply q");
    }

    /** Parses a {@code .q} file; see {@link Query#parseFile}. */
    public static List<Query> parseFile(String fileText) {
        String text = stripComments(fileText);
        List<Query> out = new ArrayList<>();
        String[] lines = text.split("\r?\n", -1);
        for (int i = 0; i < lines.length; i++) {
            if (lines[i].isBlank()) {
                continue;
            }
            out.add(onLine(lines[i], i + 1));
        }
        return out;
    }

    /**
     * Parses the query {@code written} on line {@code line} of a file (0: not from a file); one that does not
     * parse is an {@link Query.Kind#INVALID} query with the error.
     */
    public static Query onLine(String written, int line) {
        String where = line > 0 ? "line " + line + ": " : "";
        try {
            Query q = parse(written);
            return new Query(q.text(), q.kind(), q.property(), q.target(), q.reason(), q.column(), line);
        } catch (QueryException e) {
            return new Query(written.strip(), Query.Kind.INVALID, null, null, where + e.getMessage(), 0, line);
        }
    }

    /** The index of the first {@code -->} outside parentheses and brackets, or -1. */
    private static int topLevelArrow(String text) {
        int depth = 0;
        for (int i = 0; i + 2 < text.length(); i++) {
            char c = text.charAt(i);
            if (c == '(' || c == '[') {
                depth++;
            } else if (c == ')' || c == ']') {
                depth--;
            } else if (depth == 0 && text.startsWith("-->", i)) {
                return i;
            }
        }
        return -1;
    }

    private static int skipSpaces(String text, int from) {
        int i = from;
        while (i < text.length() && Character.isWhitespace(text.charAt(i))) {
            i++;
        }
        return i;
    }

    /** Replaces comments by spaces, keeping line breaks so that line numbers stay right. */
    private static String stripComments(String text) {
        StringBuilder sb = new StringBuilder(text.length());
        int i = 0;
        while (i < text.length()) {
            if (text.startsWith("//", i)) {
                while (i < text.length() && text.charAt(i) != '\n') {
                    i++;
                }
            } else if (text.startsWith("/*", i)) {
                int end = text.indexOf("*/", i + 2);
                end = end < 0 ? text.length() : end + 2;
                for (int k = i; k < end; k++) {
                    sb.append(text.charAt(k) == '\n' ? '\n' : ' ');
                }
                i = end;
            } else {
                sb.append(text.charAt(i++));
            }
        }
        return sb.toString();
    }
}
