package io.dtron.xta.internal;

import io.dtron.xta.Diagnostic;
import io.dtron.xta.Fragment;
import io.dtron.xta.Pos;
import io.dtron.xta.internal.parser.UppaalLexer;
import java.util.ArrayList;
import java.util.List;
import java.util.Set;
import java.util.TreeSet;
import org.antlr.v4.runtime.BaseErrorListener;
import org.antlr.v4.runtime.Parser;
import org.antlr.v4.runtime.RecognitionException;
import org.antlr.v4.runtime.Recognizer;
import org.antlr.v4.runtime.Token;
import org.antlr.v4.runtime.TokenStream;
import org.antlr.v4.runtime.misc.IntervalSet;

/** Turns ANTLR's syntax errors into {@link Diagnostic}s with short messages in the model's terms. */
final class SyntaxErrorCollector extends BaseErrorListener {
    private static final int MAX_EXPECTED = 6;

    private final Fragment fragment;
    private final List<Diagnostic> diagnostics = new ArrayList<>();

    SyntaxErrorCollector(Fragment fragment) {
        this.fragment = fragment;
    }

    List<Diagnostic> diagnostics() {
        return diagnostics;
    }

    @Override
    public void syntaxError(Recognizer<?, ?> recognizer, Object offendingSymbol, int line, int charPositionInLine,
                            String msg, RecognitionException e) {
        Token token = offendingSymbol instanceof Token t ? t : null;
        int start = token != null && token.getType() != Token.EOF ? token.getStartIndex() : fragment.text().length();
        int end = token != null && token.getType() != Token.EOF ? token.getStopIndex() + 1 : start;
        if (token != null && token.getType() == Token.EOF) {
            start = trimmedEnd();
            end = start;
        }
        String message;
        Token next = token == null ? null : neighbour(recognizer, token, 1);
        Token previous = token == null ? null : neighbour(recognizer, token, -1);
        if (token != null && token.getType() == UppaalLexer.UNTERMINATED_COMMENT) {
            message = "a comment starts here with '/*' but never ends with '*/'";
            end = start + 2;
        } else if (isOperator(token) && next != null && !startsExpression(next)) {
            // "3 +;": the operand is missing; say so where it should be
            message = "syntax error: an operand is missing after '" + token.getText() + "'";
            start = next.getType() == Token.EOF ? trimmedEnd() : next.getStartIndex();
            end = next.getType() == Token.EOF ? start : next.getStopIndex() + 1;
        } else if (token != null && !startsExpression(token) && isOperator(previous)) {
            message = "syntax error: an operand is missing after '" + previous.getText() + "'";
        } else {
            message = describe(recognizer, token, e);
        }
        diagnostics.add(Diagnostic.error(new Pos(fragment, start, end), message));
    }

    private static Token neighbour(Recognizer<?, ?> recognizer, Token token, int step) {
        if (!(recognizer instanceof Parser parser) || token.getTokenIndex() < 0) {
            return null;
        }
        TokenStream tokens = parser.getInputStream();
        int i = token.getTokenIndex() + step;
        return i >= 0 && i < tokens.size() ? tokens.get(i) : null;
    }

    private static final Set<String> BINARY_OPERATORS = Set.of("+", "-", "*", "/", "%", "<", "<=", ">", ">=", "==",
            "!=", "&&", "||", "&", "|", "^", "<<", ">>", "<?", ">?", "?", ":", "=", ":=", "+=", "-=", "*=", "/=", "%=",
            "and", "or", "imply", "not", "!", "**");

    private static boolean isOperator(Token token) {
        return token != null && token.getType() != Token.EOF && BINARY_OPERATORS.contains(token.getText());
    }

    private static boolean startsExpression(Token token) {
        if (token.getType() == Token.EOF) {
            return false;
        }
        String text = token.getText();
        return !(text.equals(";") || text.equals(",") || text.equals(")") || text.equals("]") || text.equals("}"));
    }

    private int trimmedEnd() {
        String t = fragment.text();
        int i = t.length();
        while (i > 0 && Character.isWhitespace(t.charAt(i - 1))) {
            i--;
        }
        return i;
    }

    private static String describe(Recognizer<?, ?> recognizer, Token token, RecognitionException e) {
        String found;
        if (token == null || token.getType() == Token.EOF) {
            found = "end of text";
        } else if (token.getType() == UppaalLexer.UNEXPECTED_CHAR) {
            found = "character '" + token.getText() + "'";
        } else {
            found = "'" + token.getText() + "'";
        }
        StringBuilder sb = new StringBuilder("syntax error: unexpected ").append(found);
        if (recognizer instanceof Parser parser) {
            IntervalSet expected = e != null && e.getExpectedTokens() != null ? e.getExpectedTokens()
                    : parser.getExpectedTokens();
            TreeSet<String> names = new TreeSet<>();
            for (int type : expected.toArray()) {
                names.add(tokenName(parser, type));
            }
            if (!names.isEmpty() && names.size() <= MAX_EXPECTED) {
                sb.append(", expected ").append(String.join(" or ", names));
            }
        }
        return sb.toString();
    }

    private static String tokenName(Parser parser, int type) {
        if (type == Token.EOF) {
            return "end of text";
        }
        String literal = parser.getVocabulary().getLiteralName(type);
        if (literal != null) {
            return literal;
        }
        String symbolic = parser.getVocabulary().getSymbolicName(type);
        return switch (symbolic == null ? "" : symbolic) {
            case "ID" -> "a name";
            case "NAT" -> "a number";
            case "FLOAT" -> "a number";
            case "STRING" -> "a string";
            case "E_EVENTUALLY" -> "'E<>'";
            case "A_GLOBALLY" -> "'A[]'";
            case "A_EVENTUALLY" -> "'A<>'";
            case "E_GLOBALLY" -> "'E[]'";
            default -> symbolic == null ? "token " + type : symbolic;
        };
    }
}
